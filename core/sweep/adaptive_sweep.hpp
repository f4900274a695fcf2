#pragma once
// adapt() with the kernel table given, so tests can count what the sweep computes, and the
// sweep's features per threshold, so tests can match them their own way.
#include <array>
#include <cstdint>
#include <vector>

#include "aief/adapt.hpp"
#include "core/frame/frame_pipeline.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/sweep/sorted_block_entropies.hpp"
#include "core/sweep/sweep_matcher.hpp"
#include "parallel/scheduler.hpp"

namespace aief {

AdaptResult adapt_with_kernels(ImageView a, ImageView b, const ExtractorOptions& options,
                               const SweepOptions& sweep, const KernelTable& kernels);

// One image at one threshold: its features and each feature's identity in the image's analysis
// (candidate index, numbered on through the levels), the same at every threshold that keeps it.
struct ThresholdFeatures {
  Features features;
  std::vector<std::int32_t> ids;
  // With Repeats::referenced, a threshold that keeps the same blocks as the one before holds
  // only features.info and names here the earlier threshold whose features it repeats.
  int repeat_of = -1;

  // The features at this threshold, wherever they are held (`all` is the image's sweep).
  const ThresholdFeatures& resolved(const std::vector<ThresholdFeatures>& all) const {
    return repeat_of >= 0 ? all[static_cast<std::size_t>(repeat_of)] : *this;
  }
};

// Whether a threshold that repeats the previous one's features gets its own copy of them.
enum class Repeats { copied, referenced };

// Both images at every threshold F_0 + c S_p of the sweep, c < ceil(E / S_p) (at least one).
struct SweepFeatures {
  double image_entropy_bits = 0;  // E of image A
  std::vector<ThresholdFeatures> a, b;
};

SweepFeatures sweep_features(ImageView a, ImageView b, const ExtractorOptions& options,
                             const SweepOptions& sweep, const KernelTable& kernels,
                             Repeats repeats = Repeats::copied);

// The sweep with everything it keeps between pairs (AdaptiveSweep's state): both analyses, every
// threshold's features and matches, one matcher per thread.
class SweepPipeline {
 public:
  // Validates the options (throws aief::Error).
  SweepPipeline(const ExtractorOptions& options, const SweepOptions& sweep,
                const KernelTable& kernels);

  void run(ImageView a, ImageView b, AdaptResult& out);
  // Analyses both images and extracts them at every threshold; valid until the next call.
  const SweepFeatures& features(ImageView a, ImageView b, Repeats repeats);

  // The same sweep in steps, each on the caller's thread, for a caller that spreads one sweep
  // over several calls (core/sweep/carried_threshold.hpp); the answer is run()'s, bit for bit. In
  // order: analyse(0, a), analyse(1, b) (the images must stay valid until the last step), then C =
  // begin_thresholds(Repeats::referenced), then for c = 0 .. C-1 in turn select_threshold(0, c),
  // select_threshold(1, c), evaluate_in_order(c); then choose(out).
  void analyse(int image, ImageView view);  // image 0 is A, 1 is B
  int begin_thresholds(Repeats repeats);    // returns C, the number of thresholds
  void select_threshold(int image, int c);  // the image's features at F_0 + c S_p
  void evaluate_in_order(int c);            // matches and model of threshold c, unless repeated
  void choose(AdaptResult& out) const;      // the curve and the choice, after every threshold

  // Each of those steps in smaller pieces, for a caller that spreads one sweep over frames with a
  // bound on each frame's work (core/sweep/spread_sweep.hpp); the steps above are made of them, so
  // the answer is the same. analyse(image, view) = start_analysis(image, view), then
  // level_entropies(image, n) and detect_level(image, n) for each n in turn.
  void start_analysis(int image, ImageView view) { frame(image).start_analysis(view); }
  int level_count(int image) { return frame(image).analysis().level_count(); }
  void level_entropies(int image, int n) { frame(image).level_entropies(n); }
  void detect_level(int image, int n) { frame(image).detect_at(n, sweep_.first_threshold); }
  // select_threshold(image, c) = the repeat of c - 1 when selects_like_previous(image, c), else
  // choose_level(image, c, n) and the descriptions of level n for each n, then
  // finish_threshold(image, c). The descriptions: prepare_descriptor_input(image, n) unless
  // descriptor_input_ready, then describe_next(image, n, k) until undescribed(image, n) is 0.
  bool selects_like_previous(int image, int c) const;
  void repeat_previous(int image, int c);
  void choose_level(int image, int c, int n);
  // Candidates level n's chosen list holds (the distribution read that many), and of those the
  // ones not described yet.
  int candidates_considered(int image, int c, int n);
  bool descriptor_input_ready(int image, int n) {
    return frame(image).analysis().descriptor_input_ready(n);
  }
  void prepare_descriptor_input(int image, int n) { frame(image).prepare_descriptor_input(n); }
  int undescribed(int image, int n);
  void describe_next(int image, int n, int count);
  void finish_threshold(int image, int c);
  // Candidates chosen over the levels (the features finish_threshold puts together).
  int chosen_total(int image) const;
  // evaluate_in_order(c) = begin_evaluation(c) (false: a repeat, nothing more to do), then the
  // matcher's rows (matcher().offer_rows) until none is left, then finish_matching(c) and
  // fit_threshold(c) (RANSAC on putative_matches(c)).
  bool begin_evaluation(int c);
  SweepMatcher& matcher() { return runs_[0].matcher; }
  void finish_matching(int c);
  int putative_matches(int c) const {
    return static_cast<int>(evaluated_[static_cast<std::size_t>(c)].matches.size());
  }
  void fit_threshold(int c) { fit(runs_[0], static_cast<std::size_t>(c)); }
  // Features of image at threshold c (after finish_threshold or repeat_previous).
  int feature_count(int image, int c) const;
  // Level n's size, for estimates of the work.
  int level_width(int image, int n) { return frame(image).analysis().level(n).geometry.width; }
  int level_height(int image, int n) { return frame(image).analysis().level(n).geometry.height; }

 private:
  // The matches of one threshold and the model fitted to them.
  struct Evaluated {
    std::vector<Match> matches;
    HomographyResult homography;
  };
  // What one thread of the matching reuses.
  struct MatchRun {
    SweepMatcher matcher;
    std::vector<Point2> src, dst;
  };

  FramePipeline& frame(int image);
  void evaluate(MatchRun& run, std::size_t c);
  void fit(MatchRun& run, std::size_t c);
  double threshold_at(int c) const { return sweep_.first_threshold + sweep_.step * c; }
  // Whether threshold c selects other features than c - 1 (both images); records its source.
  bool mark_distinct(int c);
  // Where the distinct thresholds are cut into `runs` runs (core/sweep/sweep_runs.hpp).
  std::vector<int> cut_into_runs(int runs);

  ExtractorOptions options_;
  SweepOptions sweep_;
  const KernelTable* kernels_;
  parallel::Scheduler scheduler_;
  FramePipeline frame_a_, frame_b_;  // each image's analysis, serial (the images run side by side)
  SweepFeatures features_;
  Repeats repeats_ = Repeats::copied;
  // Per image (A, B): candidate identity offsets, sorted block entropies, each level's selection
  // at the last threshold selected.
  std::array<std::vector<std::int32_t>, 2> id_offsets_;
  std::array<SortedBlockEntropies, 2> sorted_entropies_;
  std::array<std::vector<std::vector<std::int32_t>>, 2> chosen_;
  std::vector<std::int32_t> to_describe_;  // describe_next's piece
  std::vector<int> source_, distinct_;
  std::vector<Evaluated> evaluated_;
  std::vector<MatchRun> runs_;
  std::vector<int> present_at_, new_a_, new_b_;  // cut_into_runs' counts of new features
};

}  // namespace aief

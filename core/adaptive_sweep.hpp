#pragma once
// adapt() with the kernel table given, so tests can count what the sweep computes, and the
// sweep's features per threshold, so tests can match them their own way.
#include <cstdint>
#include <vector>

#include "aief/adapt.hpp"
#include "core/frame_pipeline.hpp"
#include "core/kernel_table.hpp"
#include "core/sweep_matcher.hpp"
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

  void evaluate(MatchRun& run, std::size_t c);
  // Where the distinct thresholds are cut into `runs` runs (core/sweep_runs.hpp).
  std::vector<int> cut_into_runs(int runs);

  ExtractorOptions options_;
  SweepOptions sweep_;
  const KernelTable* kernels_;
  parallel::Scheduler scheduler_;
  FramePipeline frame_a_, frame_b_;  // each image's analysis, serial (the images run side by side)
  SweepFeatures features_;
  std::vector<std::vector<std::int32_t>> chosen_a_, chosen_b_;
  std::vector<int> source_, distinct_;
  std::vector<Evaluated> evaluated_;
  std::vector<MatchRun> runs_;
  std::vector<int> present_at_, new_a_, new_b_;  // cut_into_runs' counts of new features
};

}  // namespace aief

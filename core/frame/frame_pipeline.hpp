#pragma once
// One frame through the engine, in one place: the path Extractor::extract runs, the one the
// adaptive sweep analyses each image with, and the one `aief bench` times (docs/architecture.md).
//
// Per level, in a chain (level n is made from level n - 1, and each level's work runs as soon as
// it is built, beside the levels still being built): pixels, block entropies, FAST candidates of
// the blocks F keeps, selection (distribution, orientation, descriptors). The automatic F needs
// every level's entropies first, so then detection and selection follow in a second parallel
// region. The threshold fallback (core/entropy/threshold_fallback.hpp) decides each level's F and
// budget; when its frame rules change them, the levels concerned select again. The stages
// themselves are FrameAnalysis's (core/frame/frame_analysis.hpp).
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/entropy/threshold_fallback.hpp"
#include "core/frame/frame_analysis.hpp"
#include "core/frame/stage_times.hpp"
#include "core/kernels/kernel_table.hpp"
#include "parallel/scheduler.hpp"

namespace aief {

class FramePipeline final : private CandidateSource {
 public:
  // `options` must be valid (ExtractorOptions::validate). threads as parallel::Scheduler's: 0 the
  // caller's task arena, 1 serial in the caller's thread.
  FramePipeline(const ExtractorOptions& options, const KernelTable& kernels, int threads);

  // Keypoints and descriptors of one frame, with the automatic F and the threshold fallback as
  // the options ask. Throws aief::Error for an image the options refuse. `times`, when given,
  // gets each stage's milliseconds added. detection_mask: as FrameAnalysis::start's.
  void extract(ImageView image, Features& out, StageTimes* times = nullptr,
               ImageView detection_mask = {});

  // The sweep's analysis of one image (core/sweep/adaptive_sweep.hpp): pixels, entropies and the
  // candidates of every block `lowest_threshold` keeps, every level in turn on the caller's
  // thread, no fallback (the sweep measures each F as it is). Then select() at each threshold.
  void analyse(ImageView image, double lowest_threshold, StageTimes* times = nullptr);
  // analyse() a level at a time, serial, for a caller that spreads it over frames
  // (core/sweep/spread_sweep.hpp): start_analysis(image), then for n = 0, 1, ... level_entropies(n)
  // (pixels and block entropies) and detect_at(n, F). The same analysis as analyse()'s.
  void start_analysis(ImageView image) { start(image, Selections::many, nullptr); }
  void level_entropies(int n) {
    build_level(n);
    compute_entropies(n);
  }
  void detect_at(int n, double lowest_threshold) { detect_level(n, lowest_threshold); }
  // Stage 4 alone: level n's keypoints at F with budget N_n, after analyse().
  void select(int n, double threshold, std::vector<std::int32_t>& chosen);
  // Its two parts (FrameAnalysis::choose and describe), with budget N_n.
  void choose(int n, double threshold, std::vector<std::int32_t>& chosen);
  void describe(int n, const std::vector<std::int32_t>& indices) { analysis_.describe(n, indices); }
  void prepare_descriptor_input(int n) { analysis_.prepare_descriptor_input(n); }

  const FrameAnalysis& analysis() const { return analysis_; }
  // The fixed F the next extract() requests (the carried F changes it between frames).
  void set_entropy_threshold(double threshold) { options_.entropy_threshold = threshold; }

 private:
  // CandidateSource, for the fallback: detection is the pipeline's (timed) stage 3.
  int level_count() const override { return analysis_.level_count(); }
  int level_budget(int n) const override;
  void detect_level(int n, double threshold) override;
  void detect_frame(double threshold) override;
  std::int64_t level_candidates(int n, double threshold) const override;

  void start(ImageView image, Selections selections, StageTimes* times,
             ImageView detection_mask = {});
  void build_level(int n);
  void compute_entropies(int n);
  void select_level(int n, double threshold, int budget, std::vector<std::int32_t>& chosen);
  void write_info(double requested, double effectiveness, ExtractionInfo& info) const;
  template <class Work>
  void timed(Stage stage, int n, const Work& work);

  ExtractorOptions options_;
  const KernelTable* kernels_;
  parallel::Scheduler scheduler_;
  FrameAnalysis analysis_;
  ThresholdFallback fallback_;
  StageTimes* times_ = nullptr;                    // for the frame being run
  std::vector<std::vector<std::int32_t>> chosen_;  // per level: its selection, raster order
  std::vector<double> thresholds_;                 // per level: F applied
  std::vector<int> budgets_;                       // per level: N_n, raised by the shortfall
  std::vector<double> selected_thresholds_;        // what each level first selected with
  std::vector<int> selected_budgets_;
  std::vector<double> entropies_;  // every block's, for the automatic F
};

}  // namespace aief

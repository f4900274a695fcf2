#include "aief/extractor.hpp"

#include <algorithm>

#include "core/auto_threshold.hpp"
#include "core/frame_analysis.hpp"
#include "core/level_shortfall.hpp"
#include "core/starvation_guard.hpp"
#include "parallel/scheduler.hpp"
#include "simd/kernels.hpp"

namespace aief {

struct Extractor::State {
  ExtractorOptions options;
  const KernelTable* kernels = nullptr;
  parallel::Scheduler scheduler;
  FrameAnalysis analysis;
  std::vector<std::vector<std::int32_t>> chosen;
  std::vector<double> entropies;  // all blocks' entropies, for the automatic F
  std::vector<double> level_thresholds;  // F applied per level
  std::vector<int> level_budgets, raised_budgets;  // N_n, and N_n with the shortfall handed on
  std::vector<std::int64_t> level_available;     // candidates in each level's kept blocks
};

Extractor::Extractor(ExtractorOptions options) : state_(std::make_unique<State>()) {
  options.validate();
  state_->options = options;
  state_->kernels = &kernel_table(options.kernels);
  state_->scheduler = parallel::Scheduler(options.threads);
}

Extractor::~Extractor() = default;
Extractor::Extractor(Extractor&&) noexcept = default;
Extractor& Extractor::operator=(Extractor&&) noexcept = default;

const ExtractorOptions& Extractor::options() const { return state_->options; }

std::string_view Extractor::kernel_name() const { return state_->kernels->name; }

ImageView Extractor::pyramid_level(int n) const {
  const FrameAnalysis& analysis = state_->analysis;
  if (n < 0 || n >= analysis.level_count() || !analysis.level(n).usable()) return {};
  return analysis.level(n).pixels;
}

Features Extractor::extract(ImageView image) {
  Features features;
  extract(image, features);
  return features;
}

void Extractor::extract(ImageView image, Features& out) {
  State& s = *state_;
  FrameAnalysis& analysis = s.analysis;
  analysis.start(image, s.options, *s.kernels);
  const int levels = analysis.level_count();
  s.chosen.resize(static_cast<std::size_t>(levels));
  const bool entropy_on = s.options.entropy != EntropyMeasure::off;
  const bool automatic = entropy_on && s.options.auto_threshold;
  double requested = entropy_on ? s.options.entropy_threshold : 0.0;
  const bool level_guard = entropy_on && s.options.starvation_guard == StarvationGuard::level;
  std::vector<double>& thresholds = s.level_thresholds;
  thresholds.assign(static_cast<std::size_t>(levels), requested);
  // One parallel region: the pyramid is a chain (level n from level n - 1), and each level runs
  // its entropies, detection and selection as soon as it is built, beside the levels still being
  // built. The automatic F needs every level's entropies first; detection and selection of
  // every level then follow in a second region.
  auto select_level = [&](int n) {
    double& threshold = thresholds[static_cast<std::size_t>(n)];
    if (level_guard) threshold = detect_with_level_guard(analysis, n, requested);
    else analysis.detect(n, threshold);
    analysis.select(n, threshold, s.chosen[static_cast<std::size_t>(n)]);
  };
  s.scheduler.for_each_in_chain(
      levels, [&](int n) { analysis.build_level(n); },
      [&](int n) {
        analysis.compute_entropies(n);
        if (!automatic) select_level(n);
      });
  if (automatic) {
    auto_threshold_entropies(analysis, s.entropies);
    requested = auto_entropy_threshold(s.entropies, s.options.auto_requires_two_classes).threshold_bits;
    thresholds.assign(static_cast<std::size_t>(levels), requested);
    s.scheduler.for_each(levels, select_level);
  }
  // Never starve, the frame rule (DESIGN.md section 3): while the kept blocks hold fewer
  // candidates than the features asked for, lower F for this frame, down to 0 (every non-flat
  // block), and select again. Rare: the selections above at the requested F are replaced.
  double threshold = requested;
  if (entropy_on && !level_guard && threshold > 0.0 && analysis.candidate_count(threshold) < s.options.n_features) {
    while (threshold > 0.0 && analysis.candidate_count(threshold) < s.options.n_features) {
      threshold = std::max(0.0, threshold - kStarvationStep);
      s.scheduler.for_each(levels, [&](int n) { analysis.detect(n, threshold); });
    }
    thresholds.assign(static_cast<std::size_t>(levels), threshold);
    s.scheduler.for_each(levels, [&](int n) { analysis.select(n, threshold, s.chosen[static_cast<std::size_t>(n)]); });
  }
  // The per-level rule goes on (core/level_shortfall.hpp): the budget that levels short of
  // candidates leave undelivered goes to the levels with candidates to spare, finest first, so the
  // frame delivers min(N, candidates in the kept blocks). The other modes keep their output.
  if (s.options.starvation_guard == StarvationGuard::level) {
    s.level_budgets.resize(static_cast<std::size_t>(levels));
    s.level_available.resize(static_cast<std::size_t>(levels));
    for (int n = 0; n < levels; ++n) {
      const std::size_t i = static_cast<std::size_t>(n);
      s.level_budgets[i] = analysis.level(n).usable() ? analysis.level(n).geometry.n_features : 0;
      s.level_available[i] = analysis.level_candidate_count(n, thresholds[i]);
    }
    if (raise_budgets_for_shortfall(s.level_budgets, s.level_available, s.raised_budgets))
      s.scheduler.for_each(levels, [&](int n) {
        const std::size_t i = static_cast<std::size_t>(n);
        if (s.raised_budgets[i] != s.level_budgets[i]) analysis.select(n, thresholds[i], s.raised_budgets[i], s.chosen[i]);
      });
  }
  analysis.assemble(s.chosen, out);

  ExtractionInfo& info = out.info;
  info.entropy_threshold_requested = requested;
  // With the per-level guard the levels may differ: the lowest F applied is the one reported.
  info.entropy_threshold_used = requested;
  for (int n = 0; n < levels; ++n)
    if (analysis.level(n).usable())
      info.entropy_threshold_used = std::min(info.entropy_threshold_used, thresholds[static_cast<std::size_t>(n)]);
  info.threshold_lowered = info.entropy_threshold_used < info.entropy_threshold_requested;
  info.image_entropy_bits = analysis.image_entropy_bits();
  info.blocks_total = analysis.blocks_total();
  info.blocks_kept = 0;
  for (int n = 0; n < levels; ++n) info.blocks_kept += analysis.level_blocks_kept(n, thresholds[static_cast<std::size_t>(n)]);
}

Features extract(ImageView image, const ExtractorOptions& options) {
  return Extractor(options).extract(image);
}

}  // namespace aief

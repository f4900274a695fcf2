#include "aief/extractor.hpp"

#include <algorithm>

#include "core/auto_threshold.hpp"
#include "core/frame_analysis.hpp"
#include "parallel/scheduler.hpp"
#include "simd/kernels.hpp"

namespace aief {

namespace {

// Step by which a starving frame lowers F: the sweep's S_p (DESIGN.md section 3).
constexpr double kStarvationStep = 0.2;

}  // namespace

struct Extractor::State {
  ExtractorOptions options;
  const KernelTable* kernels = nullptr;
  parallel::Scheduler scheduler;
  FrameAnalysis analysis;
  std::vector<std::vector<std::int32_t>> chosen;
  std::vector<double> entropies;  // all blocks' entropies, for the automatic F
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
  double threshold = requested;
  // One parallel region: the pyramid is a chain (level n from level n - 1), and each level runs
  // its entropies, detection and selection as soon as it is built, beside the levels still being
  // built. The automatic F needs every level's entropies first; then detection and selection
  // of every level follow in a second region.
  auto select_level = [&](int n) {
    analysis.detect(n, threshold);
    analysis.select(n, threshold, s.chosen[static_cast<std::size_t>(n)]);
  };
  s.scheduler.for_each_in_chain(
      levels, [&](int n) { analysis.build_level(n); },
      [&](int n) {
        analysis.compute_entropies(n);
        if (!automatic) select_level(n);
      });
  if (automatic) {
    s.entropies.clear();
    for (int n = 0; n < levels; ++n) {
      const std::vector<double>& level = analysis.level(n).block_entropy;
      s.entropies.insert(s.entropies.end(), level.begin(), level.end());
    }
    requested = threshold = auto_entropy_threshold(s.entropies);
    s.scheduler.for_each(levels, select_level);
  }
  // Never starve (DESIGN.md section 3): while the kept blocks hold fewer candidates than the
  // features asked for, lower F for this frame, down to 0 (every non-flat block), and select
  // again. Rare: the selections above at the requested F are then simply replaced.
  if (entropy_on && threshold > 0.0 && analysis.candidate_count(threshold) < s.options.n_features) {
    while (threshold > 0.0 && analysis.candidate_count(threshold) < s.options.n_features) {
      threshold = std::max(0.0, threshold - kStarvationStep);
      s.scheduler.for_each(levels, [&](int n) { analysis.detect(n, threshold); });
    }
    s.scheduler.for_each(levels, select_level);
  }
  analysis.assemble(s.chosen, out);

  ExtractionInfo& info = out.info;
  info.entropy_threshold_requested = requested;
  info.entropy_threshold_used = threshold;
  info.threshold_lowered = threshold < info.entropy_threshold_requested;
  info.image_entropy_bits = analysis.image_entropy_bits();
  info.blocks_total = analysis.blocks_total();
  info.blocks_kept = analysis.blocks_kept(threshold);
}

Features extract(ImageView image, const ExtractorOptions& options) {
  return Extractor(options).extract(image);
}

}  // namespace aief

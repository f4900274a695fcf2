#include "core/frame/frame_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/frame/auto_threshold.hpp"

namespace aief {

FramePipeline::FramePipeline(const ExtractorOptions& options, const KernelTable& kernels,
                             int threads)
    : options_(options), kernels_(&kernels), scheduler_(threads), fallback_(options) {}

template <class Work>
void FramePipeline::timed(Stage stage, int n, const Work& work) {
  if (times_ == nullptr) {
    work();
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  work();
  times_->add(
      stage, n,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

void FramePipeline::start(ImageView image, Selections selections, StageTimes* times,
                          ImageView detection_mask) {
  times_ = times;
  timed(Stage::frame, -1,
        [&] { analysis_.start(image, options_, *kernels_, selections, detection_mask); });
  const std::size_t levels = static_cast<std::size_t>(analysis_.level_count());
  if (times_) times_->reserve_levels(analysis_.level_count());
  chosen_.resize(levels);
  thresholds_.resize(levels);
  budgets_.resize(levels);
}

void FramePipeline::build_level(int n) {
  timed(Stage::pyramid, n, [&] { analysis_.build_level(n); });
}

void FramePipeline::compute_entropies(int n) {
  timed(Stage::entropy, n, [&] { analysis_.compute_entropies(n); });
}

void FramePipeline::select_level(int n, double threshold, int budget,
                                 std::vector<std::int32_t>& chosen) {
  timed(Stage::select, n, [&] { analysis_.select(n, threshold, budget, chosen); });
}

int FramePipeline::level_budget(int n) const {
  return analysis_.level(n).usable() ? analysis_.level(n).geometry.n_features : 0;
}

void FramePipeline::detect_level(int n, double threshold) {
  timed(Stage::detect, n, [&] { analysis_.detect(n, threshold); });
}

void FramePipeline::detect_frame(double threshold) {
  scheduler_.for_each(analysis_.level_count(), [&](int n) { detect_level(n, threshold); });
}

std::int64_t FramePipeline::level_candidates(int n, double threshold) const {
  return analysis_.level_candidate_count(n, threshold);
}

void FramePipeline::extract(ImageView image, Features& out, StageTimes* times,
                            ImageView detection_mask) {
  start(image, Selections::one, times, detection_mask);
  const int levels = analysis_.level_count();
  const bool entropy_on = options_.entropy != EntropyMeasure::off;
  const bool automatic = entropy_on && options_.auto_threshold;
  // Scale selection needs every level detected before any selects: it waits as the automatic F.
  const bool scales = options_.scale_selection != ScaleSelection::off;
  double requested = entropy_on ? options_.entropy_threshold : 0.0;
  double effectiveness = 0;
  for (int n = 0; n < levels; ++n) budgets_[static_cast<std::size_t>(n)] = level_budget(n);

  auto detect_and_select = [&](int n) {
    const std::size_t i = static_cast<std::size_t>(n);
    thresholds_[i] = fallback_.detect_level(*this, n, requested);
    select_level(n, thresholds_[i], budgets_[i], chosen_[i]);
  };
  scheduler_.for_each_in_chain(
      levels, [&](int n) { build_level(n); },
      [&](int n) {
        compute_entropies(n);
        if (!automatic && !scales) detect_and_select(n);
      });
  if (automatic) {
    timed(Stage::frame, -1, [&] {
      auto_threshold_entropies(analysis_, entropies_);
      const AutoThreshold chosen =
          auto_entropy_threshold(entropies_, options_.auto_requires_two_classes);
      requested = chosen.threshold_bits;
      effectiveness = chosen.effectiveness;
    });
  }
  if (scales) {
    // Every block of every level (whatever F keeps: a corner's scale does not depend on it), then
    // the extrema (core/detection/scale_selection.hpp); the levels select as with the automatic
    // F, each with its budget N_n, the threshold fallback and the shortfall as always.
    scheduler_.for_each(levels,
                        [&](int n) { detect_level(n, -std::numeric_limits<double>::infinity()); });
    scheduler_.for_each(
        levels, [&](int n) { timed(Stage::detect, n, [&] { analysis_.index_scales(n); }); });
    scheduler_.for_each(
        levels, [&](int n) { timed(Stage::detect, n, [&] { analysis_.mark_scale_extrema(n); }); });
    scheduler_.for_each(
        levels, [&](int n) { timed(Stage::detect, n, [&] { analysis_.keep_scale_extrema(n); }); });
  }
  if (automatic || scales) scheduler_.for_each(levels, detect_and_select);

  // The fallback's frame rules, then the levels whose F or budget they changed select again.
  selected_thresholds_ = thresholds_;
  selected_budgets_ = budgets_;
  if (fallback_.settle_frame(*this, requested, thresholds_, budgets_))
    scheduler_.for_each(levels, [&](int n) {
      const std::size_t i = static_cast<std::size_t>(n);
      if (thresholds_[i] != selected_thresholds_[i] || budgets_[i] != selected_budgets_[i])
        select_level(n, thresholds_[i], budgets_[i], chosen_[i]);
    });

  timed(Stage::frame, -1, [&] {
    analysis_.assemble(chosen_, out);
    write_info(requested, effectiveness, out.info);
  });
  times_ = nullptr;
}

void FramePipeline::write_info(double requested, double effectiveness, ExtractionInfo& info) const {
  const int levels = analysis_.level_count();
  info.entropy_threshold_requested = requested;
  // With the level rule the levels may differ: the lowest F applied is the one reported.
  info.entropy_threshold_used = requested;
  for (int n = 0; n < levels; ++n)
    if (analysis_.level(n).usable())
      info.entropy_threshold_used =
          std::min(info.entropy_threshold_used, thresholds_[static_cast<std::size_t>(n)]);
  info.threshold_lowered = info.entropy_threshold_used < info.entropy_threshold_requested;
  info.image_entropy_bits = analysis_.image_entropy_bits();
  info.auto_threshold_effectiveness = effectiveness;
  info.blocks_total = analysis_.blocks_total();
  info.blocks_kept = 0;
  for (int n = 0; n < levels; ++n)
    info.blocks_kept += analysis_.level_blocks_kept(n, thresholds_[static_cast<std::size_t>(n)]);
}

void FramePipeline::analyse(ImageView image, double lowest_threshold, StageTimes* times) {
  start(image, Selections::many, times);
  scheduler_.for_each_in_chain(
      analysis_.level_count(), [&](int n) { build_level(n); },
      [&](int n) {
        compute_entropies(n);
        detect_level(n, lowest_threshold);  // every block any threshold of the sweep keeps
      });
  times_ = nullptr;
}

void FramePipeline::choose(int n, double threshold, std::vector<std::int32_t>& chosen) {
  analysis_.choose(n, threshold, level_budget(n), chosen);
}

void FramePipeline::select(int n, double threshold, std::vector<std::int32_t>& chosen) {
  select_level(n, threshold, level_budget(n), chosen);
}

}  // namespace aief

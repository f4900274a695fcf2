#include "core/entropy/threshold_fallback.hpp"

#include <algorithm>
#include <cassert>

namespace aief {

namespace {

std::int64_t frame_candidates(const CandidateSource& frame, double threshold) {
  std::int64_t total = 0;
  for (int n = 0; n < frame.level_count(); ++n) total += frame.level_candidates(n, threshold);
  return total;
}

}  // namespace

ThresholdFallback::ThresholdFallback(const ExtractorOptions& options) {
  const bool masked = options.entropy != EntropyMeasure::off;
  level_rule_ = masked && options.starvation_guard == StarvationGuard::level;
  frame_rule_ = masked && options.starvation_guard == StarvationGuard::frame;
  shortfall_rule_ = options.starvation_guard == StarvationGuard::level;
  n_features_ = options.n_features;
}

double ThresholdFallback::detect_level(CandidateSource& frame, int n, double threshold) const {
  frame.detect_level(n, threshold);
  if (!level_rule_) return threshold;
  const int budget = frame.level_budget(n);
  if (budget <= 0) return threshold;  // a level too small to use has nothing to detect
  while (threshold > 0.0 && frame.level_candidates(n, threshold) < budget) {
    threshold = std::max(0.0, threshold - kStep);
    frame.detect_level(n, threshold);
  }
  return threshold;
}

bool ThresholdFallback::settle_frame(CandidateSource& frame, double requested,
                                     std::vector<double>& thresholds, std::vector<int>& budgets) {
  bool changed = false;
  if (frame_rule_ && requested > 0.0 && frame_candidates(frame, requested) < n_features_) {
    double threshold = requested;
    while (threshold > 0.0 && frame_candidates(frame, threshold) < n_features_) {
      threshold = std::max(0.0, threshold - kStep);
      frame.detect_frame(threshold);
    }
    thresholds.assign(thresholds.size(), threshold);
    changed = true;
  }
  if (shortfall_rule_) {
    available_.resize(budgets.size());
    for (std::size_t n = 0; n < budgets.size(); ++n)
      available_[n] = frame.level_candidates(static_cast<int>(n), thresholds[n]);
    if (raise_budgets_for_shortfall(budgets, available_, raised_)) {
      budgets.swap(raised_);
      changed = true;
    }
  }
  return changed;
}

bool raise_budgets_for_shortfall(const std::vector<int>& budgets,
                                 const std::vector<std::int64_t>& available,
                                 std::vector<int>& raised) {
  assert(budgets.size() == available.size());
  raised.assign(budgets.begin(), budgets.end());
  std::int64_t shortfall = 0;
  for (std::size_t n = 0; n < budgets.size(); ++n)
    shortfall += std::max<std::int64_t>(0, budgets[n] - available[n]);
  bool any = false;
  for (std::size_t n = 0; n < budgets.size() && shortfall > 0; ++n) {
    const std::int64_t extra = std::min(shortfall, available[n] - budgets[n]);
    if (extra <= 0) continue;
    raised[n] = budgets[n] + static_cast<int>(extra);
    shortfall -= extra;
    any = true;
  }
  return any;
}

}  // namespace aief

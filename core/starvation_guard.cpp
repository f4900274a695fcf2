#include "core/starvation_guard.hpp"

#include <algorithm>

namespace aief {

double detect_with_level_guard(FrameAnalysis& analysis, int n, double threshold) {
  analysis.detect(n, threshold);
  if (!analysis.level(n).usable()) return threshold;
  const int budget = analysis.level(n).geometry.n_features;
  while (threshold > 0.0 && analysis.level_candidate_count(n, threshold) < budget) {
    threshold = std::max(0.0, threshold - kStarvationStep);
    analysis.detect(n, threshold);
  }
  return threshold;
}

void auto_threshold_entropies(const FrameAnalysis& analysis, std::vector<double>& entropies) {
  entropies.clear();
  const bool skip_uniform = analysis.options().auto_skips_uniform_blocks;
  for (int n = 0; n < analysis.level_count(); ++n) {
    const LevelState& level = analysis.level(n);
    for (std::size_t b = 0; b < level.block_entropy.size(); ++b)
      if (!skip_uniform || !level.block_uniform[b]) entropies.push_back(level.block_entropy[b]);
  }
}

}  // namespace aief

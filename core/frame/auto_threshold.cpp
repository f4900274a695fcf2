#include "core/frame/auto_threshold.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/frame/frame_analysis.hpp"

namespace aief {

namespace {

constexpr double kBinBits = 0.05;  // histogram resolution of the split
constexpr int kBins = 64 * 20;     // entropies are < 64 bits in either measure

// Otsu's threshold: the bin edge maximising the between-class variance, and its effectiveness.
AutoThreshold otsu_split(const std::array<int, kBins>& histogram, int total) {
  double sum_all = 0, sum_squares = 0;
  for (int i = 0; i < kBins; ++i) {
    const double count = histogram[static_cast<std::size_t>(i)];
    sum_all += static_cast<double>(i) * count;
    sum_squares += static_cast<double>(i) * i * count;
  }
  double sum_low = 0, best_variance = -1;
  int count_low = 0, best_bin = 0;
  for (int i = 0; i < kBins; ++i) {
    count_low += histogram[static_cast<std::size_t>(i)];
    sum_low += static_cast<double>(i) * histogram[static_cast<std::size_t>(i)];
    const int count_high = total - count_low;
    if (count_low == 0) continue;
    if (count_high == 0) break;
    const double mean_low = sum_low / count_low, mean_high = (sum_all - sum_low) / count_high;
    const double variance = static_cast<double>(count_low) * count_high * (mean_low - mean_high) *
                            (mean_low - mean_high);
    if (variance > best_variance) {
      best_variance = variance;
      best_bin = i;
    }
  }
  // Both variances scaled by total^2: count_low * count_high * (mean difference)^2 and
  // total * sum i^2 - (sum i)^2, in bins (the unit cancels).
  const double total_variance = static_cast<double>(total) * sum_squares - sum_all * sum_all;
  AutoThreshold split;
  split.threshold_bits = (best_bin + 1) * kBinBits;  // blocks in bins <= best_bin fall below F
  split.effectiveness =
      total_variance > 0 && best_variance > 0 ? std::min(1.0, best_variance / total_variance) : 0.0;
  return split;
}

}  // namespace

AutoThreshold auto_entropy_threshold(std::vector<double>& entropies, bool require_two_classes) {
  if (entropies.empty()) return {};
  std::array<int, kBins> histogram{};
  for (double e : entropies) {
    const int bin = std::clamp(static_cast<int>(e / kBinBits), 0, kBins - 1);
    ++histogram[static_cast<std::size_t>(bin)];
  }
  const int total = static_cast<int>(entropies.size());
  AutoThreshold split = otsu_split(histogram, total);
  if (require_two_classes && split.effectiveness < kAutoMinEffectiveness) {
    split.threshold_bits = 0.0;  // one population: no block is low-information relative to the rest
    return split;
  }
  double threshold = split.threshold_bits;

  // Keep at least kAutoMinKeptShare of the blocks: F no higher than the entropy below which
  // the other blocks lie (a block is kept when E > F).
  std::vector<double>& sorted = entropies;
  const std::size_t dropped_at_most =
      static_cast<std::size_t>(std::floor((1.0 - kAutoMinKeptShare) * total));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(dropped_at_most),
                   sorted.end());
  const double cap = std::nextafter(sorted[dropped_at_most], 0.0);
  threshold = std::min(threshold, std::max(cap, 0.0));
  split.threshold_bits = std::max(threshold, 0.0);
  return split;
}

void auto_threshold_entropies(const FrameAnalysis& analysis, std::vector<double>& entropies) {
  entropies.clear();
  const bool skip_uniform = analysis.options().auto_skips_uniform_blocks;
  for (int n = 0; n < analysis.level_count(); ++n) {
    const LevelBlocks& blocks = analysis.blocks(n);
    for (std::size_t b = 0; b < blocks.entropy_bits.size(); ++b)
      if (!skip_uniform || !blocks.uniform[b]) entropies.push_back(blocks.entropy_bits[b]);
  }
}

}  // namespace aief

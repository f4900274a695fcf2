#include "core/auto_threshold.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace aief {

namespace {

constexpr double kBinBits = 0.05;  // histogram resolution of the split
constexpr int kBins = 64 * 20;     // entropies are < 64 bits in either measure

// Otsu's threshold: the bin edge maximising the between-class variance.
double otsu_split(const std::array<int, kBins>& histogram, int total) {
  double sum_all = 0;
  for (int i = 0; i < kBins; ++i) sum_all += static_cast<double>(i) * histogram[static_cast<std::size_t>(i)];
  double sum_low = 0, best_variance = -1;
  int count_low = 0, best_bin = 0;
  for (int i = 0; i < kBins; ++i) {
    count_low += histogram[static_cast<std::size_t>(i)];
    sum_low += static_cast<double>(i) * histogram[static_cast<std::size_t>(i)];
    const int count_high = total - count_low;
    if (count_low == 0) continue;
    if (count_high == 0) break;
    const double mean_low = sum_low / count_low, mean_high = (sum_all - sum_low) / count_high;
    const double variance = static_cast<double>(count_low) * count_high * (mean_low - mean_high) * (mean_low - mean_high);
    if (variance > best_variance) {
      best_variance = variance;
      best_bin = i;
    }
  }
  return (best_bin + 1) * kBinBits;  // blocks in bins <= best_bin fall below F
}

}  // namespace

double auto_entropy_threshold(std::vector<double>& entropies) {
  if (entropies.empty()) return 0.0;
  std::array<int, kBins> histogram{};
  for (double e : entropies) {
    const int bin = std::clamp(static_cast<int>(e / kBinBits), 0, kBins - 1);
    ++histogram[static_cast<std::size_t>(bin)];
  }
  const int total = static_cast<int>(entropies.size());
  double threshold = otsu_split(histogram, total);

  // Keep at least kAutoMinKeptShare of the blocks: F no higher than the entropy below which
  // the other blocks lie (a block is kept when E > F).
  std::vector<double>& sorted = entropies;
  const std::size_t dropped_at_most = static_cast<std::size_t>(std::floor((1.0 - kAutoMinKeptShare) * total));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(dropped_at_most), sorted.end());
  const double cap = std::nextafter(sorted[dropped_at_most], 0.0);
  threshold = std::min(threshold, std::max(cap, 0.0));
  return std::max(threshold, 0.0);
}

}  // namespace aief

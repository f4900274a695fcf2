#include "core/sweep/sorted_block_entropies.hpp"

#include <algorithm>
#include <utility>

namespace aief {

SortedBlockEntropies::SortedBlockEntropies(const FrameAnalysis& analysis)
    : levels_(static_cast<std::size_t>(analysis.level_count())) {
  for (int n = 0; n < analysis.level_count(); ++n) {
    std::vector<double>& sorted = levels_[static_cast<std::size_t>(n)];
    sorted = analysis.blocks(n).entropy_bits;
    std::sort(sorted.begin(), sorted.end());
  }
}

bool SortedBlockEntropies::same_level_blocks_kept(int n, double f, double g) const {
  if (f > g) std::swap(f, g);
  const std::vector<double>& sorted = levels_[static_cast<std::size_t>(n)];
  const auto first_above_f = std::upper_bound(sorted.begin(), sorted.end(), f);
  return first_above_f == sorted.end() || *first_above_f > g;
}

bool SortedBlockEntropies::same_blocks_kept(double f, double g) const {
  for (int n = 0; n < static_cast<int>(levels_.size()); ++n)
    if (!same_level_blocks_kept(n, f, g)) return false;
  return true;
}

int SortedBlockEntropies::blocks_kept(double f) const {
  std::size_t kept = 0;
  for (const std::vector<double>& sorted : levels_)
    kept +=
        static_cast<std::size_t>(sorted.end() - std::upper_bound(sorted.begin(), sorted.end(), f));
  return static_cast<int>(kept);
}

}  // namespace aief

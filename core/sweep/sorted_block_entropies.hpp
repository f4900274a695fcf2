#pragma once
// Each level's block entropies in ascending order, to compare thresholds without visiting every
// block: Eq. 9 keeps a block when its entropy e > F, so thresholds F < G keep the same blocks of a
// level exactly when no e has F < e <= G, and F keeps the blocks above the first e > F. The
// adaptive sweep (core/sweep/adaptive_sweep.hpp) asks it which thresholds select the same features.
#include <vector>

#include "core/frame/frame_analysis.hpp"

namespace aief {

class SortedBlockEntropies {
 public:
  SortedBlockEntropies() = default;
  // Every block of every usable level of `analysis` (the sweep needs an entropy measure).
  explicit SortedBlockEntropies(const FrameAnalysis& analysis);

  // Whether thresholds F and G keep the same blocks of level n: then the level selects the same
  // candidates (its distribution depends on its kept blocks alone).
  bool same_level_blocks_kept(int n, double f, double g) const;
  // The same on every level: then F and G select the same features.
  bool same_blocks_kept(double f, double g) const;
  int blocks_kept(double f) const;

 private:
  std::vector<std::vector<double>> levels_;
};

}  // namespace aief

#pragma once
// Stage 3 as ORB-SLAM2/3's ComputeKeyPointsOctTree does it (the faithful mode's detection,
// docs/design.md §5, "ORB-SLAM's own cells"). A level's keypoint area [16, size - 16) is cut into
// cells of about 35 pixels (ORB-SLAM3; ORB-SLAM2 has 30): n = floor((size - 32) / 35) cells of
// ceil((size - 32) / n) pixels per axis (the last ones clipped). Each cell runs cv::FAST(cell
// image, t, nonmax) on its cell grown by 6 pixels (3 on each side for the ring), at iniThFAST, and
// again at minThFAST when that gave nothing. Because every cell is its own image, suppression at a
// cell's edge compares with 0 outside it: a corner on the last row of one cell survives beside a
// stronger one on the first row of the next, which the engine's level-wide suppression would
// remove. Candidates come in ORB-SLAM's order: cells row by row, raster order within a cell; the
// octree's tie-breaks (core/distribution/octree_orbslam.hpp) depend on it.
//
// How, in one pass over the level instead of one per cell: a corner at t survives its cell's
// suppression when s >= t and s > every neighbour inside the cell's scored area (a neighbour at
// or above s is a corner at t too, since s >= t). Inside that area all 8 neighbours are in it, so
// there a cell's corners are the level's local maxima at t, which the FAST kernels give as bits
// once per level (fast9_scores_row at fast_min_threshold, fast9_local_maxima_bits with
// fast_threshold as the strong bound). A cell row's first and last scored rows take the same
// kernel against a zero row above (below); only the first and last column of each cell, whose
// left (right) neighbours lie outside, are tested one by one. Overlapping cells share the bits.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/distribution/candidate.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

inline constexpr int kOrbSlamCellSide = 35;   // ORB-SLAM3's W (ORB-SLAM2 has 30)
inline constexpr int kOrbSlamMinBorder = 16;  // EDGE_THRESHOLD - 3: the cells' and octree's origin

// The level's score map and local-maxima bit rows, reused from frame to frame.
struct OrbSlamCellScratch {
  std::vector<std::uint8_t> scores;   // width x height, 0 outside the scored area
  std::vector<std::uint64_t> maxima;  // per row: local maxima (s >= fast_min_threshold)
  std::vector<std::uint64_t> strong;  // per row: those with s >= fast_threshold
  std::vector<std::uint64_t> ring_maxima, ring_strong;  // a cell row's first and last scored row
  std::vector<std::uint8_t> zero_row;                   // the row outside a cell's scored area
};

// The candidates of a level of `pixels` in ORB-SLAM's order, appended to `out`. Levels whose
// keypoint area is under one cell in a side give none (ORB-SLAM would divide by zero there).
void detect_orbslam_cells(ImageView pixels, const ExtractorOptions& options,
                          const KernelTable& kernels, OrbSlamCellScratch& scratch,
                          std::vector<Candidate>& out);

}  // namespace aief

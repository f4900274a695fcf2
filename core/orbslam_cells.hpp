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
// octree's tie-breaks (core/octree_orbslam.hpp) depend on it.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/candidate.hpp"
#include "core/kernel_table.hpp"

namespace aief {

inline constexpr int kOrbSlamCellSide = 35;   // ORB-SLAM3's W (ORB-SLAM2 has 30)
inline constexpr int kOrbSlamMinBorder = 16;  // EDGE_THRESHOLD - 3: the cells' and octree's origin

// The candidates of a level of `pixels` in ORB-SLAM's order, appended to `out`. `scores` is reused
// storage. Levels whose keypoint area is under one cell in a side give none (ORB-SLAM would
// divide by zero there).
void detect_orbslam_cells(ImageView pixels, const ExtractorOptions& options,
                          const KernelTable& kernels, std::vector<std::uint8_t>& scores,
                          std::vector<Candidate>& out);

}  // namespace aief

#pragma once
// FAST-9 corner score and 3x3 non-maximum suppression, exactly as OpenCV's
// cv::FAST(img, kps, t, /*nonmaxSuppression=*/true) (docs/design.md §5).
//
// Score of a pixel p with ring pixels r_0..r_15 (Bresenham circle, radius 3, OpenCV's order):
//   s = max over the 16 arcs of 9 contiguous ring pixels of
//         max(min over the arc of (p - r_k), min over the arc of (r_k - p))   minus 1
// i.e. the largest t for which the strict test (all 9 > p + t, or all 9 < p - t) passes.
// A pixel is a corner at threshold t exactly when s >= t, so the score does not depend on t.
// Suppression: a corner survives when its score is > the score of all 8 neighbours, where a
// neighbour that is not a corner at t counts 0. Because a candidate has s >= t, that equals
// "s > every neighbour's raw score": the local maxima do not depend on t either, and one score
// map serves both thresholds of a block and every F of the sweep.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

// Ring offsets (dx, dy) in OpenCV's order, starting straight up and turning clockwise.
inline constexpr int kFastRingDx[16] = {0, 1, 2, 3, 3, 3, 2, 1, 0, -1, -2, -3, -3, -3, -2, -1};
inline constexpr int kFastRingDy[16] = {-3, -3, -2, -1, 0, 1, 2, 3, 3, 3, 2, 1, 0, -1, -2, -3};

// Scores of the pixels x in [x_begin, x_end) of the row at `center` (pointer to pixel x = 0 of
// that row; rows are `stride` bytes apart). Writes scores[x] (same x indexing) = the score
// above when it is >= min_threshold, else 0. Reads rows -3..+3 and columns x-3..x+3, so the
// caller keeps x_begin >= 3, x_end <= width - 3 and the row at least 3 from the top and bottom.
// min_threshold >= 1.
void fast9_scores_row_scalar(const std::uint8_t* center, std::ptrdiff_t stride, int x_begin,
                             int x_end, int min_threshold, std::uint8_t* scores);

}  // namespace aief

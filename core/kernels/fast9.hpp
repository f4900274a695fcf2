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

// Local maxima of one score row, as bits: bit i of maxima[i / 64] (bit i % 64, least
// significant first) is set when x = x_begin + i has row[x] > 0 and row[x] > each of its 8
// neighbours in above/row/below (x - 1 .. x + 1); the same bit of strong[] when, besides,
// row[x] >= strong_threshold. Writes all fast9_maxima_words(x_end - x_begin) words of both, unused
// high bits 0. Reads above/row/below at x_begin - 1 .. x_end. One call covers a whole run of
// blocks; a block then takes its bit range, strong or all (ORB-SLAM2's retry rule), without
// a pass over its candidates.
constexpr int fast9_maxima_words(int width) { return (width + 63) / 64; }
void fast9_local_maxima_bits_scalar(const std::uint8_t* above, const std::uint8_t* row,
                                    const std::uint8_t* below, int x_begin, int x_end,
                                    int strong_threshold, std::uint64_t* maxima,
                                    std::uint64_t* strong);

}  // namespace aief

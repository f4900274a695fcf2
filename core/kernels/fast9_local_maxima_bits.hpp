#pragma once
// FAST-9's 3x3 non-maximum suppression over rows of scores (core/kernels/fast9_scores_row.hpp),
// exactly as OpenCV's cv::FAST(img, kps, t, /*nonmaxSuppression=*/true) (docs/design.md §5).
#include <cstdint>

namespace aief {

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

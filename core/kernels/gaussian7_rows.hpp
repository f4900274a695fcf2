#pragma once
// 7x7 Gaussian, sigma 2, separable, Q8 fixed point, BORDER_REFLECT_101 (docs/design.md §7).
//   taps kGaussian7Q8: OpenCV's 8-bit fixed-point kernel for 7x7 sigma 2, so the blur is
//   cv::GaussianBlur(src, dst, {7, 7}, 2, 2, BORDER_REFLECT_101) to the byte (tested)
//   h(x)  = sum_k taps[k] * src[y][reflect101(x + k - 3)]          <= 65280, fits uint16
//   dst   = (sum_k taps[k] * h(reflect101(y + k - 3)) + 32768) >> 16
// Integer throughout, so every instruction set gives the same bytes.
#include <array>
#include <cstdint>

#include "aief/image.hpp"

namespace aief {

inline constexpr std::array<std::uint16_t, 7> kGaussian7Q8 = {18, 34, 48, 56, 48, 34, 18};

// Blurs columns [x_begin, x_end) of rows [y_begin, y_end) of src into dst: dst row i holds
// blurred row y_begin + i at the same columns (its other columns are left as they are), so dst
// may be the whole plane (y_begin = 0) or a band of y_end - y_begin rows, and a caller may blur
// only the columns it reads. dst is src's width, 0 <= x_begin <= x_end <= width, src's width
// and height are >= 4, and they do not overlap. Reads src rows y_begin - 3 .. y_end + 2 and
// columns x_begin - 3 .. x_end + 2 (reflected at the edges).
void gaussian7_rows_scalar(ImageView src, MutableImageView dst, int y_begin, int y_end, int x_begin,
                           int x_end);

}  // namespace aief

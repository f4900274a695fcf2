#pragma once
// 7x7 Gaussian, sigma 2, separable, Q8 fixed point, BORDER_REFLECT_101 (DESIGN.md section 1).
//   taps kGaussian7Q8 = round(256 * g_k / sum g), centre adjusted so the taps sum to 256
//   h(x)  = sum_k taps[k] * src[y][reflect101(x + k - 3)]          <= 65280, fits uint16
//   dst   = (sum_k taps[k] * h(reflect101(y + k - 3)) + 32768) >> 16
// Integer throughout, so every instruction set gives the same bytes.
#include <array>
#include <cstdint>

#include "aief/image.hpp"

namespace aief {

inline constexpr std::array<std::uint16_t, 7> kGaussian7Q8 = {18, 34, 49, 54, 49, 34, 18};

// Writes dst rows [y_begin, y_end); src and dst have the same size, width and height >= 4,
// and do not overlap. Reads src rows y_begin - 3 .. y_end + 2 (reflected at the edges).
void gaussian7_rows_scalar(ImageView src, MutableImageView dst, int y_begin, int y_end);

}  // namespace aief

#pragma once
// One row of the integral image the box descriptor reads (core/kernels/integral_image.hpp): row
// y + 1 from row y and the image's row y,
//   out[0] = 0,   out[x + 1] = above[x + 1] + (pixels[0] + ... + pixels[x])   for x in [0, width)
// in uint32 arithmetic (modulo 2^32, as the integral image is held). Integer adds only, so any
// order of them (a vector prefix sum) gives the same bytes.
#include <cstdint>

namespace aief {

// `pixels` holds width (>= 1) bytes, `above` and `out` width + 1 entries; out overlaps neither.
// Reads nothing past them.
void integral_image_row_scalar(const std::uint8_t* pixels, int width, const std::uint32_t* above,
                               std::uint32_t* out);

// Entries x + 1 .. width of the row, from pixel x on, `row_sum` being pixels[0] + ... +
// pixels[x - 1]: the reference's loop, the scalar kernel's whole row (from x = 0) and each vector
// kernel's tail.
inline void integral_image_row_from(const std::uint8_t* pixels, int x, std::uint32_t row_sum,
                                    int width, const std::uint32_t* above, std::uint32_t* out) {
  for (; x < width; ++x) {
    row_sum += pixels[x];
    out[x + 1] = above[x + 1] + row_sum;
  }
}

}  // namespace aief

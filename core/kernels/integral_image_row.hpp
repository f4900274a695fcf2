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

}  // namespace aief

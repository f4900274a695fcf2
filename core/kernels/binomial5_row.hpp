#pragma once
// One row of the 5x5 binomial blur, in integers (docs/design.md §5, "detection on a smoothed
// level"; the kernel behind core/detection/detection_smoothing.hpp):
//   column sums  v(x)  = s(x, y-2) + 4 s(x, y-1) + 6 s(x, y) + 4 s(x, y+1) + s(x, y+2)   <= 4080
//   blur * 256   b(x)  = v(x-2) + 4 v(x-1) + 6 v(x) + 4 v(x+1) + v(x+2)                 <= 65280
//   out(x)       = (b(x) + 128) >> 8
// with rows and columns outside the image replicated from its edge (BORDER_REPLICATE), the blur of
// core/kernels/unsharp_row.hpp. The binomial taps (1 4 6 4 1) / 16 have variance 1 (sigma 1 px);
// k passes in a row have variance k. Integers throughout, so every instruction set gives the same
// bytes.
#include <cstdint>

#include "aief/image.hpp"

namespace aief {

// Row y of `src` blurred into dst[0, src.width). `column_sums` is scratch of src.width + 4
// entries. src is not empty, 0 <= y < src.height; reads src rows y - 2 .. y + 2 (clamped to the
// image); dst does not overlap src or column_sums.
void binomial5_row_scalar(ImageView src, int y, std::uint16_t* column_sums, std::uint8_t* dst);

// The vertical pass both 5x5 kernels share (this blur and core/kernels/unsharp_row.hpp's): the
// column sums v(x) of row y for x = -2 .. src.width + 1 into column_sums[0, src.width + 4), the
// two outer ones on each side replicated; returns column_sums + 2, which is v(0).
std::uint16_t* binomial5_column_sums(ImageView src, int y, std::uint16_t* column_sums);

}  // namespace aief

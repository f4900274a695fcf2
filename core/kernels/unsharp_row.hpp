#pragma once
// One row of an unsharp mask with a per-pixel amount, in integers (docs/design.md §5, "sharpened
// low-entropy blocks"; the kernel behind core/entropy/low_entropy_sharpen.hpp):
//   column sums  v(x)  = s(x, y-2) + 4 s(x, y-1) + 6 s(x, y) + 4 s(x, y+1) + s(x, y+2)   <= 4080
//   blur * 256   b(x)  = v(x-2) + 4 v(x-1) + 6 v(x) + 4 v(x+1) + v(x+2)                 <= 65280
//   detail       d(x)  = 256 s(x, y) - b(x)                                  in [-65280, 65280]
//   out(x) = clamp(s(x, y) + floor((a(x) d(x) + 2^15) / 2^16), 0, 255)
// the 5x5 binomial blur (sigma 1) with rows and columns outside the image replicated from its
// edge (BORDER_REPLICATE), a(x) the amount in 1/256 (256: the detail added once more). An amount
// of 0 gives the row unchanged. |a d| <= 512 * 65280 < 2^25, so every step fits 32-bit integers
// and every instruction set gives the same bytes.
#include <cstdint>

#include "aief/image.hpp"

namespace aief {

// Largest amount the kernel takes, 1/256: 2.0.
inline constexpr int kUnsharpMaxAmountQ8 = 512;

// Row y of `src` sharpened into dst[0, src.width). amount_q8[x] in [0, kUnsharpMaxAmountQ8] for
// every x < src.width; `column_sums` is scratch of src.width + 4 entries. src is not empty,
// 0 <= y < src.height; reads src rows y - 2 .. y + 2 (clamped to the image); dst does not overlap
// src, amount_q8 or column_sums.
void unsharp_row_scalar(ImageView src, int y, const std::int16_t* amount_q8,
                        std::uint16_t* column_sums, std::uint8_t* dst);

}  // namespace aief

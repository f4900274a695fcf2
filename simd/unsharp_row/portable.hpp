#pragma once
// The unsharp mask row, for every set: the contract of core/kernels/unsharp_row.hpp, the same
// bytes.
//
// Written for the compiler's vectoriser, not with xsimd batches: both passes are straight loops
// over restrict-qualified rows (the u8 -> u16 vertical sums, then the 32-bit blur, detail,
// multiply by the amount and clamp), which GCC and Clang vectorise at the width of the unit's
// flags (kernels_<set>.cpp); xsimd 8.1 has no widening load from bytes to 16 or 32-bit lanes.
// Every operation is the reference's integer operation, so the vector and scalar paths (and the
// vectoriser's tail) give the same bytes. Measured: callgrind instructions of the sharpening
// stage in docs/design.md §5.
#include <cstdint>

#include "core/kernels/unsharp_row.hpp"
#include "simd/binomial5_row/portable.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void unsharp_row(ImageView src, int y, const std::int16_t* amount_q8, std::uint16_t* column_sums,
                 std::uint8_t* dst) {
  const int width = src.width;
  const std::uint8_t* __restrict r2 = src.row(y);
  const std::uint16_t* __restrict v = binomial5_vertical_pass(src, y, column_sums);
  const std::int16_t* __restrict amount = amount_q8;
  std::uint8_t* __restrict out = dst;
  for (int x = 0; x < width; ++x) {
    const std::int32_t blur = v[x - 2] + v[x + 2] + 4 * (v[x - 1] + v[x + 1]) + 6 * v[x];
    const std::int32_t detail = 256 * r2[x] - blur;
    const std::int32_t added = ((amount[x] * detail + (1 << 15) + (1 << 26)) >> 16) - (1 << 10);
    const std::int32_t sharpened = r2[x] + added;
    out[x] = static_cast<std::uint8_t>(sharpened < 0 ? 0 : (sharpened > 255 ? 255 : sharpened));
  }
}

AIEF_SIMD_NAMESPACE_END

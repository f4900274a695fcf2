#pragma once
// The binomial blur row, for every set: the contract of core/kernels/binomial5_row.hpp, the same
// bytes.
//
// Written for the compiler's vectoriser, as simd/unsharp_row_portable.hpp (whose blur it is):
// both passes are straight loops over restrict-qualified rows (the u8 -> u16 vertical sums, then
// the horizontal sum and rounding), which GCC and Clang vectorise at the width of the unit's flags
// (kernels_<set>.cpp). Every operation is the reference's integer operation, so the vector and
// scalar paths (and the vectoriser's tail) give the same bytes.
#include <cstdint>

#include "core/kernels/binomial5_row.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

// The vertical pass both 5x5 kernels share, for the vectoriser (binomial5_column_sums' contract,
// core/kernels/binomial5_row.hpp): column sums of row y into column_sums, v(0) returned.
inline std::uint16_t* binomial5_vertical_pass(ImageView src, int y, std::uint16_t* column_sums) {
  const int width = src.width, last_row = src.height - 1;
  const std::uint8_t* __restrict r0 = src.row(y >= 2 ? y - 2 : 0);
  const std::uint8_t* __restrict r1 = src.row(y >= 1 ? y - 1 : 0);
  const std::uint8_t* __restrict r2 = src.row(y);
  const std::uint8_t* __restrict r3 = src.row(y + 1 <= last_row ? y + 1 : last_row);
  const std::uint8_t* __restrict r4 = src.row(y + 2 <= last_row ? y + 2 : last_row);
  std::uint16_t* __restrict v = column_sums + 2;
  for (int x = 0; x < width; ++x)
    v[x] = static_cast<std::uint16_t>(r0[x] + r4[x] + 4 * (r1[x] + r3[x]) + 6 * r2[x]);
  v[-2] = v[-1] = v[0];
  v[width] = v[width + 1] = v[width - 1];
  return v;
}

template <class Arch>
void binomial5_row(ImageView src, int y, std::uint16_t* column_sums, std::uint8_t* dst) {
  const int width = src.width;
  const std::uint16_t* __restrict v = binomial5_vertical_pass(src, y, column_sums);
  std::uint8_t* __restrict out = dst;
  for (int x = 0; x < width; ++x) {
    const std::uint32_t blur =
        static_cast<std::uint32_t>(v[x - 2] + v[x + 2]) + 4u * (v[x - 1] + v[x + 1]) + 6u * v[x];
    out[x] = static_cast<std::uint8_t>((blur + 128) >> 8);
  }
}

AIEF_SIMD_NAMESPACE_END

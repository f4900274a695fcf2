#pragma once
// The binomial blur row, for every set: the contract of core/kernels/binomial5_row.hpp, the same
// bytes.
//
// Written for the compiler's vectoriser, as simd/unsharp_row/portable.hpp (whose blur it is):
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

// xsimd batches of uint16 lanes (8, 16 a vector; the AVX-512 table takes the AVX2 instance): every
// sum fits (v(x) <= 4080, b(x) + 128 <= 65408), so each lane computes the reference's integers.
// Two vectors a step (one pack and store for both), then one more if a whole one is left, then
// one vector overlapping the one before (the same values written twice) instead of a scalar
// tail; rows narrower than a vector take the reference. 4 v(x-1) + 6 v(x) + 4 v(x+1) is
// 2 (2 (v(x-1) + v(x) + v(x+1)) + v(x)): shifts and adds, as for the column sums.
// Callgrind, graf quality mode (AVX2, 10 levels, 2 passes): 12.14 M instructions a frame with
// the vectoriser's loops and their scalar tails, 9.95 M a vector a step, 8.24 M this way.
template <class Arch>
void binomial5_row(ImageView src, int y, std::uint16_t* column_sums, std::uint8_t* dst) {
  using U16 = xsimd::batch<std::uint16_t, Arch>;
  constexpr int kLanes = static_cast<int>(U16::size);
  const int width = src.width, last_row = src.height - 1;
  if (width < kLanes) {
    binomial5_row_scalar(src, y, column_sums, dst);
    return;
  }
  const std::uint8_t* r0 = src.row(y >= 2 ? y - 2 : 0);
  const std::uint8_t* r1 = src.row(y >= 1 ? y - 1 : 0);
  const std::uint8_t* r2 = src.row(y);
  const std::uint8_t* r3 = src.row(y + 1 <= last_row ? y + 1 : last_row);
  const std::uint8_t* r4 = src.row(y + 2 <= last_row ? y + 2 : last_row);
  std::uint16_t* v = column_sums + 2;
  // outer + 4 inner + 6 centre = outer + 2 (2 (inner + centre) + centre)
  const auto taps = [](const U16& outer, const U16& inner, const U16& centre) {
    return outer + ((((inner + centre) << 1) + centre) << 1);
  };
  const auto vertical = [&](int x) {
    return taps(load_widened<Arch>(r0 + x) + load_widened<Arch>(r4 + x),
                load_widened<Arch>(r1 + x) + load_widened<Arch>(r3 + x),
                load_widened<Arch>(r2 + x));
  };
  int x = 0;
  for (; x + 2 * kLanes <= width; x += 2 * kLanes) {
    const U16 first = vertical(x), second = vertical(x + kLanes);
    first.store_unaligned(v + x);
    second.store_unaligned(v + x + kLanes);
  }
  if (x + kLanes <= width) {
    vertical(x).store_unaligned(v + x);
    x += kLanes;
  }
  if (x < width) vertical(width - kLanes).store_unaligned(v + width - kLanes);
  v[-2] = v[-1] = v[0];
  v[width] = v[width + 1] = v[width - 1];
  const U16 rounding(128);
  const auto horizontal = [&](int x) {
    const U16 blur = taps(U16::load_unaligned(v + x - 2) + U16::load_unaligned(v + x + 2),
                          U16::load_unaligned(v + x - 1) + U16::load_unaligned(v + x + 1),
                          U16::load_unaligned(v + x));
    return (blur + rounding) >> 8;
  };
  for (x = 0; x + 2 * kLanes <= width; x += 2 * kLanes)
    store_narrowed_pair<Arch>(dst + x, horizontal(x), horizontal(x + kLanes));
  if (x + kLanes <= width) {
    store_narrowed<Arch>(dst + x, horizontal(x));
    x += kLanes;
  }
  if (x < width) store_narrowed<Arch>(dst + width - kLanes, horizontal(width - kLanes));
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// 7x7 Gaussian, vectorised: the contract of core/gaussian_blur.hpp, the same bytes.
//
// The filter is separable and exact in integers, so the passes may run in either order.
// Vertical first, per column: v = sum_k w_k src[y + k - 3][x] <= 65280, in u16 lanes, stored
// biased as the int16 v - 32768 (an xor of the top bit). Horizontal: pmaddwd multiplies pairs of
// int16 and adds each pair into an int32 lane, so with the pairs (v[x-3], v[x-2]), (v[x-1],
// v[x]), (v[x+1], v[x+2]), (v[x+3], -) against (w0, w1), (w2, w3), (w4, w5), (w6, 0):
//   P = sum_t w_t (v_t - 32768) = S - 2^23   (the taps sum to 256),   |P| <= 2^23,
//   dst = (S + 32768) >> 16 = (P + 2^23 + 2^15) >> 16,
// every step an exact integer operation. A 32-bit lane loaded at v + x - 3 holds exactly the
// pair (v[x-3], v[x-2]), so a register loaded there serves the even outputs x, x + 2, ... and
// one loaded at v + x - 2 the odd ones; the two results interleave back into bytes.
//
// The mirror border: a column's vertical sum is the same wherever the column is used, so the
// few columns left and right of the row are copies of the mirrored ones (BORDER_REFLECT_101).
//
// The register operations (blur_detail::Vec<Arch>) are per instruction-set family:
// simd/gaussian_blur_x86.hpp (pmaddwd) and simd/gaussian_blur_neon.hpp (vmull + vpadd).
#include <cstdint>

#include "core/gaussian_blur.hpp"
#include "simd/simd_support.hpp"
#if defined(__aarch64__)
#include "simd/gaussian_blur_neon.hpp"
#else
#include "simd/gaussian_blur_x86.hpp"
#endif

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

template <class Arch>
void gaussian7_rows(ImageView src, MutableImageView dst, int y_begin, int y_end, int x_begin, int x_end) {
  using Ops = blur_detail::Vec<Arch>;
  using V = typename Ops::V;
  constexpr int L = Ops::kColumns;
  constexpr int kChunk = 512;  // output pixels per chunk: its columns stay in L1
  const int width = src.width, height = src.height;
  const auto& w = kGaussian7Q8;
  const auto mirror = [](int i, int size) { return i < 0 ? -i : (i >= size ? 2 * size - 2 - i : i); };
  // Biased vertical sums of a chunk's columns x0 - 4 .. x1 + 3.
  alignas(64) std::int16_t column[kChunk + 8];

  const V w0 = Ops::set16(w[0]), w1 = Ops::set16(w[1]), w2 = Ops::set16(w[2]), w3 = Ops::set16(w[3]);
  const V pair01 = Ops::set32(w[0] | w[1] << 16), pair23 = Ops::set32(w[2] | w[3] << 16);
  const V pair45 = Ops::set32(w[4] | w[5] << 16), pair6 = Ops::set32(w[6]);
  const V rounding = Ops::set32((1 << 23) + (1 << 15));

  for (int y = y_begin; y < y_end; ++y) {
    const std::uint8_t* rows[7];
    for (int k = 0; k < 7; ++k) rows[k] = src.row(mirror(y + k - 3, height));
    std::uint8_t* out = dst.row(y - y_begin);
    const auto vertical_scalar = [&](int x) {
      std::uint32_t v = 0;
      for (int k = 0; k < 7; ++k) v += w[static_cast<std::size_t>(k)] * rows[k][x];
      return static_cast<std::int16_t>(v ^ 0x8000u);
    };
    for (int x0 = x_begin; x0 < x_end; x0 += kChunk) {
      const int x1 = x0 < x_end - kChunk ? x0 + kChunk : x_end;
      const int origin = x0 - 4;  // column[i] is the vertical sum of column origin + i

      // Vertical pass over the columns inside the row, [c0, c1); symmetric taps: rows k and
      // 6 - k share a weight, added first (<= 510).
      const int c0 = x0 > 3 ? x0 - 3 : 0, c1 = x1 + 3 < width ? x1 + 3 : width;
      const auto vertical = [&](int c) {
        const V sum = Ops::add16(
            Ops::add16(Ops::mul16(Ops::add16(Ops::columns(rows[0] + c), Ops::columns(rows[6] + c)), w0),
                       Ops::mul16(Ops::add16(Ops::columns(rows[1] + c), Ops::columns(rows[5] + c)), w1)),
            Ops::add16(Ops::mul16(Ops::add16(Ops::columns(rows[2] + c), Ops::columns(rows[4] + c)), w2),
                       Ops::mul16(Ops::columns(rows[3] + c), w3)));
        Ops::store(column + (c - origin), Ops::bias(sum));
      };
      int c = c0;
      for (; c + L <= c1; c += L) vertical(c);
      if (c < c1) {
        if (c1 - c0 >= L) vertical(c1 - L);  // one overlapping last batch
        else for (; c < c1; ++c) column[c - origin] = vertical_scalar(c);
      }
      // The other columns the horizontal loads read, x0 - 4 .. x1 + 3 (x0 - 4 and x1 + 3 only
      // under a zero weight, but defined all the same): mirror images outside the row.
      const auto other_column = [&](int q) -> std::int16_t {
        if (q >= 0 && q < width) return vertical_scalar(q);
        if (q >= -3 && q < width + 3) return column[mirror(q, width) - origin];
        return 0;
      };
      for (int q = origin; q < c0; ++q) column[q - origin] = other_column(q);
      for (int q = c1; q < x1 + 4; ++q) column[q - origin] = other_column(q);

      // Horizontal pass, L outputs a step: L / 2 even ones and L / 2 odd ones.
      const auto horizontal = [&](const std::int16_t* v) {  // v = column of the output's tap 0
        return Ops::shift_down16(Ops::add32(
            Ops::add32(Ops::add32(Ops::madd(Ops::load(v), pair01), Ops::madd(Ops::load(v + 2), pair23)),
                       Ops::add32(Ops::madd(Ops::load(v + 4), pair45), Ops::madd(Ops::load(v + 6), pair6))),
            rounding));
      };
      const auto step = [&](int x) {
        const std::int16_t* v = column + (x - 3 - origin);
        Ops::store_outputs(out + x, horizontal(v), horizontal(v + 1));
      };
      int x = x0;
      for (; x + L <= x1; x += L) step(x);
      if (x < x1) {
        if (x1 - x0 >= L) {
          step(x1 - L);  // one overlapping last step: the same bytes rewritten
        } else {
          for (; x < x1; ++x) {
            const std::int16_t* v = column + (x - 3 - origin);
            std::int32_t p = 0;
            for (int t = 0; t < 7; ++t) p += w[static_cast<std::size_t>(t)] * v[t];
            out[x] = static_cast<std::uint8_t>((p + (1 << 23) + (1 << 15)) >> 16);
          }
        }
      }
    }
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

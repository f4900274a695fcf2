#pragma once
// 7x7 Gaussian, vectorised: the contract of core/kernels/gaussian7_rows.hpp, the same bytes.
//
// The filter is separable and exact in integers, so the passes may run in either order.
// Vertical first, per column: v = sum_k w_k src[y + k - 3][x] <= 65280, in u16 lanes, stored
// biased as the int16 v - kBias, kBias = 32640 (|v - kBias| <= 32640). Horizontal: pmaddwd
// multiplies pairs of int16 and adds each pair into an int32 lane, so with the pairs (v[x-3],
// v[x-2]), (v[x-1], v[x]), (v[x+1], v[x+2]), (v[x+3], -) against (w0, w1), (w2, w3), (w4, w5), (w6,
// 0):
//   P = sum_t w_t (v_t - kBias) = S - 256 kBias = S + 2^15 - 2^23   (the taps sum to 256),
//   dst = (S + 32768) >> 16 = (P + 2^23) >> 16,  i.e. P >> 16 (arithmetic) is dst - 128,
// every step an exact integer operation (the rounding term is folded into the bias). A 32-bit
// lane loaded at v + x - 3 holds exactly the pair (v[x-3], v[x-2]), so a register loaded there
// serves the even outputs x, x + 2, ... and one loaded at v + x - 2 the odd ones; the two results
// interleave back into bytes.
//
// The mirror border: a column's vertical sum is the same wherever the column is used, so the
// few columns left and right of the row are copies of the mirrored ones (BORDER_REFLECT_101).
//
// The register operations (gaussian7_rows_detail::Registers<Arch>) are per instruction-set family:
// simd/gaussian7_rows/registers_x86.hpp (pmaddwd) and simd/gaussian7_rows/registers_neon.hpp (vmull
// + vpadd).
#include <cstdint>
#include <type_traits>

#include "core/kernels/gaussian7_rows.hpp"
#include "simd/simd_support.hpp"
#if defined(__aarch64__)
#include "simd/gaussian7_rows/registers_neon.hpp"
#else
#include "simd/gaussian7_rows/registers_x86.hpp"
#endif

AIEF_SIMD_NAMESPACE_BEGIN

namespace gaussian7_rows_detail {

// The vertical pass of kRows consecutive rows at the L columns from c: a window of 7 source rows
// slides down the band, so each source row is loaded once per band instead of once per output
// row that reads it (7 loads an output row before, 1 now; callgrind, graf, AVX2). rows[k] is the
// source row of band row k - 3 (mirrored); column[j] the biased vertical sums of band row j.
template <class Registers, int kRows>
inline void vertical_band(const std::uint8_t* const* rows, std::int16_t* const* column, int c,
                          typename Registers::V w0, typename Registers::V w1,
                          typename Registers::V w2, typename Registers::V w3) {
  using V = typename Registers::V;
  V r0 = Registers::columns(rows[0] + c), r1 = Registers::columns(rows[1] + c),
    r2 = Registers::columns(rows[2] + c), r3 = Registers::columns(rows[3] + c),
    r4 = Registers::columns(rows[4] + c), r5 = Registers::columns(rows[5] + c);
#pragma GCC unroll 8
  for (int j = 0; j < kRows; ++j) {
    const V r6 = Registers::columns(rows[j + 6] + c);
    // Symmetric taps: rows k and 6 - k share a weight, added first (<= 510).
    const V sum = Registers::add16(
        Registers::add16(Registers::mul16(Registers::add16(r0, r6), w0),
                         Registers::mul16(Registers::add16(r1, r5), w1)),
        Registers::add16(Registers::mul16(Registers::add16(r2, r4), w2), Registers::mul16(r3, w3)));
    Registers::store(column[j] + c, Registers::bias(sum));
    r0 = r1;
    r1 = r2;
    r2 = r3;
    r3 = r4;
    r4 = r5;
    r5 = r6;
  }
}

// The scalar fallbacks and the mirror columns, out of line: rarely run (rows narrower than a
// vector, spans at a row's ends), but inlined, their set-up (GCC vectorises them) cost the
// kernel ~500 instructions a call (callgrind, graf, AVX2).
[[gnu::noinline]] inline void vertical_band_scalar(const std::uint8_t* const* rows,
                                                   std::int16_t* const* column, int band_rows,
                                                   int c0, int c1) {
  const auto& w = kGaussian7Q8;
  for (int j = 0; j < band_rows; ++j)
    for (int c = c0; c < c1; ++c) {
      std::uint32_t v = 0;
      for (int k = 0; k < 7; ++k) v += w[static_cast<std::size_t>(k)] * rows[j + k][c];
      column[j][c] = static_cast<std::int16_t>(static_cast<int>(v) - kBias);
    }
}

// Columns outside the row: mirror images (BORDER_REFLECT_101); width + 3 is read only under a
// zero weight, and its mirror image may lie left of the row, so it is set to 0.
[[gnu::noinline]] inline void mirror_columns(std::int16_t* const* column, int band_rows, int x0,
                                             int x1, int c0, int c1, int width) {
  for (int j = 0; j < band_rows; ++j) {
    std::int16_t* const col = column[j];
    for (int q = x0 - 3; q < c0; ++q) col[q] = col[-q];
    for (int q = c1; q < x1 + 4; ++q)
      col[q] = q < width + 3 ? col[2 * width - 2 - q] : std::int16_t{0};
  }
}

[[gnu::noinline]] inline void horizontal_scalar(const std::int16_t* column, int x0, int x1,
                                                std::uint8_t* out) {
  const auto& w = kGaussian7Q8;
  for (int x = x0; x < x1; ++x) {
    std::int32_t p = 0;
    for (int t = 0; t < 7; ++t) p += w[static_cast<std::size_t>(t)] * column[x - 3 + t];
    out[x] = static_cast<std::uint8_t>((p + (1 << 23)) >> 16);
  }
}

}  // namespace gaussian7_rows_detail

template <class Arch>
void gaussian7_rows(ImageView src, MutableImageView dst, int y_begin, int y_end, int x_begin,
                    int x_end) {
  using Registers = gaussian7_rows_detail::Registers<Arch>;
  using V = typename Registers::V;
  constexpr int L = Registers::kColumns;
  constexpr int kChunk = 512;  // output pixels per chunk: its columns stay in L1
  const int width = src.width, height = src.height;
  const std::ptrdiff_t stride = src.stride;
  const auto& w = kGaussian7Q8;
  const auto mirror = [](int i, int size) {
    return i < 0 ? -i : (i >= size ? 2 * size - 2 - i : i);
  };
  // Biased vertical sums of a chunk's columns x0 - 3 .. x1 + 3 at column[kSlack + q - (x0 - 3)];
  // the slack on both sides takes the vector loop's batches that start left of x0 - 3 or end
  // right of x1 + 3 (still inside the row).
  constexpr int kSlack = L;
  constexpr int kBandRows =
      8;  // rows whose vertical sums are kept at once (core/description/patch_blur.hpp)
  alignas(64) std::int16_t column_buffer[kBandRows][kSlack + kChunk + 7 + kSlack];

  // opaque: multiplied by constants, the compiler would rewrite each pmullw as 3-4 shifts and adds.
  const V w0 = Registers::opaque(Registers::set16(w[0])),
          w1 = Registers::opaque(Registers::set16(w[1]));
  const V w2 = Registers::opaque(Registers::set16(w[2])),
          w3 = Registers::opaque(Registers::set16(w[3]));
  // (and constant pairs would become memory operands, the columns then needing loads of their own).
  const V pair01 = Registers::opaque(Registers::set32(w[0] | w[1] << 16)),
          pair23 = Registers::opaque(Registers::set32(w[2] | w[3] << 16));
  const V pair45 = Registers::opaque(Registers::set32(w[4] | w[5] << 16)),
          pair6 = Registers::opaque(Registers::set32(w[6]));

  // Chunks outside, rows inside: a chunk's bounds and edge handling are worked out once for all
  // rows. Rows go in bands of kBandRows: the vertical pass of the whole band first, then the
  // horizontal one, so the horizontal loads (unaligned, each spanning two of the vertical pass's
  // stores) find those stores long written to L1 instead of waiting on store forwarding.
  for (int x0 = x_begin; x0 < x_end; x0 += kChunk) {
    const int x1 = x0 < x_end - kChunk ? x0 + kChunk : x_end;
    // The columns the horizontal pass reads that lie inside the row, [c0, c1); x1 + 3 is read
    // only under a zero weight.
    const int c0 = x0 > 3 ? x0 - 3 : 0, c1 = x1 + 4 < width ? x1 + 4 : width;
    const bool vector_columns = width >= L;
    const bool vector_outputs = x1 - x0 >= L;
    const auto column_row = [&](int band_row) {
      return column_buffer[band_row] + kSlack - (x0 - 3);
    };  // [q]: column q

    for (int y0 = y_begin; y0 < y_end; y0 += kBandRows) {
      const int y1 = y0 < y_end - kBandRows ? y0 + kBandRows : y_end;
      const int band_rows = y1 - y0;
      // Source rows y0 - 3 .. y1 + 2 (mirrored at the top and bottom).
      const std::uint8_t* rows[kBandRows + 6];
      if (y0 >= 3 && y1 + 3 <= height) {
        rows[0] = src.row(y0 - 3);
        for (int k = 1; k < band_rows + 6; ++k) rows[k] = rows[k - 1] + stride;
      } else {
        for (int k = 0; k < band_rows + 6; ++k) rows[k] = src.row(mirror(y0 + k - 3, height));
      }
      std::int16_t* columns[kBandRows];
      for (int j = 0; j < band_rows; ++j) columns[j] = column_row(j);

      if (vector_columns) {
        // Batches from c0 on; one that would pass the row's end starts at width - L instead
        // (within the slack, and the columns it recomputes get the same sums).
        const auto vertical = [&](auto rows_constant) {
          constexpr int kRows = decltype(rows_constant)::value;
          int c = c0;
          for (; c < c1 && c <= width - L; c += L)
            gaussian7_rows_detail::vertical_band<Registers, kRows>(rows, columns, c, w0, w1, w2,
                                                                   w3);
          if (c < c1)
            gaussian7_rows_detail::vertical_band<Registers, kRows>(rows, columns, width - L, w0, w1,
                                                                   w2, w3);
        };
        switch (band_rows) {
          case 8: vertical(std::integral_constant<int, 8>{}); break;
          case 7: vertical(std::integral_constant<int, 7>{}); break;
          case 6: vertical(std::integral_constant<int, 6>{}); break;
          case 5: vertical(std::integral_constant<int, 5>{}); break;
          case 4: vertical(std::integral_constant<int, 4>{}); break;
          case 3: vertical(std::integral_constant<int, 3>{}); break;
          case 2: vertical(std::integral_constant<int, 2>{}); break;
          default: vertical(std::integral_constant<int, 1>{}); break;
        }
      } else {
        gaussian7_rows_detail::vertical_band_scalar(rows, columns, band_rows, c0, c1);
      }
      if (x0 - 3 < c0 || c1 < x1 + 4)
        gaussian7_rows_detail::mirror_columns(columns, band_rows, x0, x1, c0, c1, width);

      for (int y = y0; y < y1; ++y) {
        const std::int16_t* const column = column_row(y - y0);
        std::uint8_t* out = dst.row(y - y_begin);
        // Horizontal pass, L outputs a step: L / 2 even ones and L / 2 odd ones, as P (above).
        const auto horizontal = [&](const std::int16_t* v) {  // v = column of the output's tap 0
          return Registers::add32(Registers::add32(Registers::madd(Registers::load(v), pair01),
                                                   Registers::madd(Registers::load(v + 2), pair23)),
                                  Registers::add32(Registers::madd(Registers::load(v + 4), pair45),
                                                   Registers::madd(Registers::load(v + 6), pair6)));
        };
        if constexpr (Registers::kMaskedTail) {
          int x = x0;
          for (; x <= x1 - L; x += L)
            Registers::store_outputs(out + x, horizontal(column + x - 3),
                                     horizontal(column + x - 2));
          if (x < x1)
            Registers::store_outputs_masked(out + x, horizontal(column + x - 3),
                                            horizontal(column + x - 2), x1 - x);
        } else if (vector_outputs) {
          // The last step overlaps the one before when the chunk is not a multiple of L: the
          // same bytes rewritten, and no column outside [x0, x1) is written.
          const auto step = [&](int x) {
            Registers::store_outputs(out + x, horizontal(column + x - 3),
                                     horizontal(column + x - 2));
          };
          int x = x0;
          if constexpr (Registers::kPairedStores) {
            // Two steps a pass where the span allows, one store of 2L bytes (callgrind, graf, AVX2:
            // 0.1 M fewer instructions); each step's pairs made before the next step's loads, or
            // the compiler runs out of registers.
            for (; x <= x1 - 2 * L; x += 2 * L) {
              const V first =
                  Registers::output_pairs(horizontal(column + x - 3), horizontal(column + x - 2));
              const V second = Registers::output_pairs(horizontal(column + x + L - 3),
                                                       horizontal(column + x + L - 2));
              Registers::store_output_pairs(out + x, first, second);
            }
          }
          for (; x <= x1 - L; x += L) step(x);
          if (x < x1) step(x1 - L);
        } else {
          gaussian7_rows_detail::horizontal_scalar(column, x0, x1, out);
        }
      }
    }
  }
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// 7x7 Gaussian, vectorised: the contract of core/gaussian_blur.hpp, the same bytes.
//
// The filter is separable and exact in integers, so the passes may run in either order:
// vertical first, v = sum_k w_k src[y + k - 3][x] <= 65280 fits u16; then horizontal. The
// horizontal sum S = sum_j w_j v_j needs 24 bits, but with v = 256 a + b,
//   (S + 32768) >> 16 == (A + (B >> 8) + 128) >> 8,  A = sum w_j a_j, B = sum w_j b_j,
// and A, B and the bracket stay below 65536: everything runs in u16 lanes. Bytes are loaded as
// u16 lanes and split into even and odd pixels (b & 255, b >> 8), so no widening instruction is
// needed; the even and odd results are merged back the same way.
#include <cstdint>

#include "core/gaussian_blur.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {

template <class Arch>
void gaussian7_rows(ImageView src, MutableImageView dst, int y_begin, int y_end) {
  using U16 = xsimd::batch<std::uint16_t, Arch>;
  constexpr int N = static_cast<int>(U16::size);  // pairs of pixels per batch
  constexpr int kChunk = 512;                     // output pixels per chunk (even)
  constexpr int kPairs = kChunk / 2 + 4 + 2 * N;  // v pairs a chunk needs, with room for a full last batch
  const int width = src.width, height = src.height;
  const auto& w = kGaussian7Q8;
  const auto mirror = [](int i, int size) { return i < 0 ? -i : (i >= size ? 2 * size - 2 - i : i); };

  alignas(64) std::uint16_t ve[kPairs], vo[kPairs];      // v of even / odd pixels of the chunk
  alignas(64) std::uint8_t tail[2 * N];                  // a last partial batch of output
  const U16 low_byte(std::uint16_t(255)), half(std::uint16_t(128));

  for (int y = y_begin; y < y_end; ++y) {
    const std::uint8_t* rows[7];
    for (int k = 0; k < 7; ++k) rows[k] = src.row(mirror(y + k - 3, height));
    std::uint8_t* out = dst.row(y - y_begin);
    for (int x0 = 0; x0 < width; x0 += kChunk) {
      const int x1 = x0 < width - kChunk ? x0 + kChunk : width;
      const int origin = x0 - 4;              // pixel of pair 0's even half
      const int pairs = (x1 - x0) / 2 + 5;    // pairs whose v the outputs read (odd widths: one more)
      // Vertical pass, pairs [0, pairs) plus the rest of their last batch. Batches whose 2N source
      // pixels lie in the row run as vectors. At the row's ends a vertical sum is the same for a
      // column and its mirror image, so the vector batch moves inside the row and only the few
      // pixels it leaves out are summed one by one (mirrored; beyond width + 2 they only feed
      // outputs that are never stored, and are 0).
      const auto vector_batch = [&](int i) {  // pairs i .. i + N - 1, pixels origin + 2i ..
        const int p = origin + 2 * i;
        // Symmetric taps: rows k and 6 - k share a weight, add them first (<= 510, no overflow).
        const auto load = [&](int k) { return U16::load_unaligned(reinterpret_cast<const std::uint16_t*>(rows[k] + p)); };
        const U16 centre = load(3);
        U16 even = (centre & low_byte) * U16(w[3]), odd = (centre >> 8) * U16(w[3]);
        for (int k = 0; k < 3; ++k) {
          const U16 top = load(k), bottom = load(6 - k);
          const U16 weight(w[static_cast<std::size_t>(k)]);
          even += ((top & low_byte) + (bottom & low_byte)) * weight;
          odd += ((top >> 8) + (bottom >> 8)) * weight;
        }
        even.store_unaligned(ve + i);
        odd.store_unaligned(vo + i);
      };
      const auto scalar_pixels = [&](int q_begin, int q_end) {  // pixels [q_begin, q_end)
        for (int q = q_begin; q < q_end; ++q) {
          const int j = (q - origin) / 2;
          if (j >= kPairs) break;
          std::uint32_t v = 0;
          if (q < width + 3)
            for (int k = 0; k < 7; ++k) v += w[static_cast<std::size_t>(k)] * rows[k][mirror(q, width)];
          ((q - origin) % 2 ? vo : ve)[j] = static_cast<std::uint16_t>(v);
        }
      };
      const bool vector_edges = width >= 2 * N + 8;
      for (int i = 0; i < pairs; i += N) {
        const int p = origin + 2 * i;
        if (p >= 0 && p + 2 * N <= width) {
          vector_batch(i);
        } else if (vector_edges && p < 0) {  // the left end: origin = -4, pixels -4 .. -1 mirror 4 .. 1
          vector_batch(i - p / 2);
          scalar_pixels(p, 0);
        } else if (const int room = width - 2 * N - origin; vector_edges && p > 0 && room >= 0) {
          vector_batch(room / 2);  // the right end: the last batch that fits, then what it leaves out
          scalar_pixels(origin + 2 * (room / 2) + 2 * N, p + 2 * N);
        } else {
          scalar_pixels(p, p + 2 * N);
        }
      }
      // Horizontal pass: output pixel x0 + 2j reads v(x0 + 2j - 3 .. + 3) = vo[j], ve[j+1], vo[j+1],
      // ve[j+2], vo[j+2], ve[j+3], vo[j+3]; the odd one x0 + 2j + 1 reads ve[j+1] .. ve[j+4].
      for (int j = 0; 2 * j < x1 - x0; j += N) {
        // Tap t of the even output is pixel x0 + 2j + t - 3 (even t from vo, odd t from ve); of
        // the odd output, one pixel further. Taps t and 6 - t share a weight: add their bytes first.
        const auto even_tap = [&](int t) { return U16::load_unaligned(t % 2 == 0 ? vo + j + t / 2 : ve + j + (t + 1) / 2); };
        const auto odd_tap = [&](int t) { return U16::load_unaligned(t % 2 == 0 ? ve + j + t / 2 + 1 : vo + j + (t + 1) / 2); };
        const U16 centre_weight(w[3]);
        const U16 even_centre = even_tap(3), odd_centre = odd_tap(3);
        U16 a_even = (even_centre >> 8) * centre_weight, b_even = (even_centre & low_byte) * centre_weight;
        U16 a_odd = (odd_centre >> 8) * centre_weight, b_odd = (odd_centre & low_byte) * centre_weight;
        for (int t = 0; t < 3; ++t) {
          const U16 weight(w[static_cast<std::size_t>(t)]);
          const U16 e0 = even_tap(t), e1 = even_tap(6 - t), o0 = odd_tap(t), o1 = odd_tap(6 - t);
          a_even += ((e0 >> 8) + (e1 >> 8)) * weight;
          b_even += ((e0 & low_byte) + (e1 & low_byte)) * weight;
          a_odd += ((o0 >> 8) + (o1 >> 8)) * weight;
          b_odd += ((o0 & low_byte) + (o1 & low_byte)) * weight;
        }
        const U16 even_out = (a_even + (b_even >> 8) + half) >> 8;
        const U16 odd_out = (a_odd + (b_odd >> 8) + half) >> 8;
        const U16 merged = even_out | (odd_out << 8);
        const int x = x0 + 2 * j;
        if (x + 2 * N <= x1) {
          merged.store_unaligned(reinterpret_cast<std::uint16_t*>(out + x));
        } else {
          merged.store_unaligned(reinterpret_cast<std::uint16_t*>(tail));
          for (int i = 0; i < x1 - x; ++i) out[x + i] = tail[i];
        }
      }
    }
  }
}

}  // namespace aief::simd

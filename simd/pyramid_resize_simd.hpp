#pragma once
// Q8 bilinear downsampling, vectorised: the contract of core/pyramid_resize.hpp, the same bytes.
//
// The formula is exact in integers, so the passes may swap: vertical first for every source
// column the chunk needs, v = src[sy][x] (256 - wy) + src[sy + 1][x] wy <= 65280 in u16 lanes;
// then per output pixel (v[sx] (256 - wx) + v[sx + 1] wx + 32768) >> 16. With AVX2 the pair
// v[sx], v[sx + 1] comes from one 32-bit gather (scale 2) and the sum runs in 32-bit lanes.
#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "core/pyramid_resize.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {

template <class Arch>
void resize_bilinear_rows(ImageView src, const ResizePlan& plan, MutableImageView dst, int y_begin, int y_end) {
  constexpr int kChunk = 256;                  // output pixels per chunk
  constexpr int kSpan = 4 * kChunk + 64;       // source columns a chunk may need (scale <= 4)
  alignas(64) std::uint16_t v[kSpan + 16];
  constexpr bool kAvx2 = std::is_base_of_v<xsimd::avx2, Arch>;
  const int dst_width = plan.dst_width;

  for (int y = y_begin; y < y_end; ++y) {
    const int sy = plan.y_index[static_cast<std::size_t>(y)];
    const std::uint16_t wy = plan.y_weight[static_cast<std::size_t>(y)];
    const std::uint8_t* top = src.row(sy);
    const std::uint8_t* bottom = src.row(sy + 1);
    std::uint8_t* out = dst.row(y);
    for (int x0 = 0; x0 < dst_width; x0 += kChunk) {
      const int x1 = std::min(dst_width, x0 + kChunk);
      const int s0 = plan.x_index[static_cast<std::size_t>(x0)];
      const int s1 = plan.x_index[static_cast<std::size_t>(x1 - 1)] + 2;  // one past the last tap
      // Vertical pass over source columns [s0, s1).
      int s = s0;
      if constexpr (kAvx2) {
        const __m256i w_top = _mm256_set1_epi16(static_cast<short>(256 - wy)), w_bottom = _mm256_set1_epi16(static_cast<short>(wy));
        for (; s + 16 <= s1; s += 16) {
          const __m256i a = _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(top + s)));
          const __m256i b = _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(bottom + s)));
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(v + (s - s0)),
                              _mm256_add_epi16(_mm256_mullo_epi16(a, w_top), _mm256_mullo_epi16(b, w_bottom)));
        }
      } else {
        const __m128i w_top = _mm_set1_epi16(static_cast<short>(256 - wy)), w_bottom = _mm_set1_epi16(static_cast<short>(wy));
        for (; s + 8 <= s1; s += 8) {
          const __m128i a = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(top + s)));
          const __m128i b = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(bottom + s)));
          _mm_storeu_si128(reinterpret_cast<__m128i*>(v + (s - s0)), _mm_add_epi16(_mm_mullo_epi16(a, w_top), _mm_mullo_epi16(b, w_bottom)));
        }
      }
      for (; s < s1; ++s) v[s - s0] = static_cast<std::uint16_t>(top[s] * (256 - wy) + bottom[s] * wy);
      v[s1 - s0] = 0;  // the gather below reads 32 bits at the last tap pair

      // Horizontal pass.
      int x = x0;
      if constexpr (kAvx2) {
        const __m256i base = _mm256_set1_epi32(s0);
        const __m256i low16 = _mm256_set1_epi32(0xffff), full = _mm256_set1_epi32(256), round = _mm256_set1_epi32(32768);
        for (; x + 8 <= x1; x += 8) {
          const __m256i sx = _mm256_sub_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(plan.x_index.data() + x)), base);
          const __m256i wx = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(plan.x_weight.data() + x)));
          const __m256i pair = _mm256_i32gather_epi32(reinterpret_cast<const int*>(v), sx, 2);
          const __m256i left = _mm256_and_si256(pair, low16), right = _mm256_srli_epi32(pair, 16);
          const __m256i sum = _mm256_add_epi32(_mm256_mullo_epi32(left, _mm256_sub_epi32(full, wx)), _mm256_mullo_epi32(right, wx));
          const __m256i result = _mm256_srli_epi32(_mm256_add_epi32(sum, round), 16);  // 0..255 per 32-bit lane
          const __m128i packed16 = _mm_packus_epi32(_mm256_castsi256_si128(result), _mm256_extracti128_si256(result, 1));
          _mm_storel_epi64(reinterpret_cast<__m128i*>(out + x), _mm_packus_epi16(packed16, packed16));
        }
      }
      for (; x < x1; ++x) {
        const int i = plan.x_index[static_cast<std::size_t>(x)] - s0;
        const std::uint32_t wx = plan.x_weight[static_cast<std::size_t>(x)];
        out[x] = static_cast<std::uint8_t>((v[i] * (256 - wx) + v[i + 1] * wx + 32768) >> 16);
      }
    }
  }
}

}  // namespace aief::simd

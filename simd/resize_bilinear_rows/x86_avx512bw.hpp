#pragma once
// Q8 bilinear downsampling with AVX-512BW: the contract of core/kernels/resize_bilinear_rows.hpp,
// the same bytes.
//
// Vertical first, then horizontal: the sum is one integer whichever pass runs first,
//   S = sum over the four taps = v(sx) (256 - wx) + v(sx + 1) wx,  v(x) = top[x] (256 - wy) +
//   bottom[x] wy,
// and 0 <= v <= 65280. Per wide group of 16 outputs (ResizePlan::x_wide_*): the 32 source
// columns of its window widened to u16, v = (top << 8) + (bottom - top) wy (exact modulo 2^16,
// and v < 2^16), biased to the int16 v - 32768; one vpermw (a 32-word table, AVX-512BW) puts
// v(sx), v(sx + 1) of each output into a 32-bit lane, and pmaddwd with (256 - wx, wx) gives
// P = S - 2^23 (the weights sum to 256), so dst = (S + 32768) >> 16 = (P + 2^23 + 2^15) >> 16,
// 0..255, narrowed by vpmovdb. About 15 instructions per 16 outputs, where the 128-bit-lane
// kernel (simd/resize_bilinear_rows/x86.hpp) runs the horizontal taps on both rows (~36).
// Rows whose plan has no wide groups (more than about 2x downscaling, narrow levels) take that
// kernel.
#include <cstdint>

#include <immintrin.h>

#include "core/kernels/resize_bilinear_rows.hpp"
#include "simd/resize_bilinear_rows/x86.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void resize_bilinear_rows_avx512(ImageView src, const ResizePlan& plan, MutableImageView dst,
                                 int y_begin, int y_end) {
  if (plan.x_wide_groups == 0) {
    resize_bilinear_rows<xsimd::avx2>(src, plan, dst, y_begin, y_end);
    return;
  }
  const int groups = plan.x_wide_groups;
  const std::int32_t* first = plan.x_wide_first.data();
  const std::int32_t* start = plan.x_wide_start.data();
  const std::int16_t* index = plan.x_wide_index.data();
  const std::int16_t* weight = plan.x_wide_weight.data();
  const __m512i bias = _mm512_set1_epi16(static_cast<short>(0x8000));
  const __m512i rounding = _mm512_set1_epi32((1 << 23) + (1 << 15));
  for (int y = y_begin; y < y_end; ++y) {
    const int sy = plan.y_index[static_cast<std::size_t>(y)];
    const __m512i wy =
        _mm512_set1_epi16(static_cast<short>(plan.y_weight[static_cast<std::size_t>(y)]));
    const std::uint8_t* top = src.row(sy);
    const std::uint8_t* bottom = src.row(sy + 1);
    std::uint8_t* out = dst.row(y);
    for (int g = 0; g < groups; ++g) {
      const int s = start[g];
      const __m512i t =
          _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(top + s)));
      const __m512i b =
          _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(bottom + s)));
      const __m512i v = _mm512_xor_si512(
          _mm512_add_epi16(_mm512_slli_epi16(t, 8), _mm512_mullo_epi16(_mm512_sub_epi16(b, t), wy)),
          bias);
      const __m512i taps = _mm512_permutexvar_epi16(_mm512_loadu_si512(index + 32 * g), v);
      const __m512i p = _mm512_madd_epi16(taps, _mm512_loadu_si512(weight + 32 * g));
      const __m512i r = _mm512_srli_epi32(_mm512_add_epi32(p, rounding), 16);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + first[g]), _mm512_cvtepi32_epi8(r));
    }
  }
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// One integral image row, vectorised: the contract of core/kernels/integral_image_row.hpp, the
// same entries (integer adds only; uint32 wraps alike in any order).
//
// A prefix sum within a vector in uint16 lanes (eight pixels sum to at most 2040), widened to
// uint32, plus the carry of the row so far (a broadcast of the last lane) and the row above.
// AVX2 and AVX-512 take 16 pixels a step: the two 128-bit lanes' prefix sums (shifts within each
// lane), the low lane's total broadcast into the high lane. SSE4.2 takes 8 a step. The tail is
// the reference's loop from the carry.
#include <immintrin.h>

#include <cstdint>
#include <type_traits>

#include "core/kernels/integral_image_row.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void integral_image_row(const std::uint8_t* pixels, int width, const std::uint32_t* above,
                        std::uint32_t* out) {
  out[0] = 0;
  int x = 0;
  std::uint32_t row_sum = 0;
  if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    const auto load = [](const std::uint32_t* p) {
      return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
    };
    const __m256i last_lane = _mm256_set1_epi32(7);
    __m256i carry = _mm256_setzero_si256();
    for (; x + 16 <= width; x += 16) {
      __m256i p = _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(pixels + x)));
      p = _mm256_add_epi16(p, _mm256_slli_si256(p, 2));
      p = _mm256_add_epi16(p, _mm256_slli_si256(p, 4));
      p = _mm256_add_epi16(p, _mm256_slli_si256(p, 8));
      // word 7 of each 128-bit lane in all its words; the low lane's moved to the high lane
      __m256i total = _mm256_shufflehi_epi16(p, 0xFF);
      total = _mm256_unpackhi_epi64(total, total);
      p = _mm256_add_epi16(p, _mm256_permute2x128_si256(total, total, 0x08));
      const __m256i low = _mm256_add_epi32(_mm256_cvtepu16_epi32(_mm256_castsi256_si128(p)), carry);
      const __m256i high =
          _mm256_add_epi32(_mm256_cvtepu16_epi32(_mm256_extracti128_si256(p, 1)), carry);
      carry = _mm256_permutevar8x32_epi32(high, last_lane);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + x + 1),
                          _mm256_add_epi32(low, load(above + x + 1)));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + x + 9),
                          _mm256_add_epi32(high, load(above + x + 9)));
    }
    row_sum = static_cast<std::uint32_t>(_mm256_cvtsi256_si32(carry));
  } else {
    const auto load = [](const std::uint32_t* p) {
      return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    };
    __m128i carry = _mm_setzero_si128();
    for (; x + 8 <= width; x += 8) {
      __m128i p = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(pixels + x)));
      p = _mm_add_epi16(p, _mm_slli_si128(p, 2));
      p = _mm_add_epi16(p, _mm_slli_si128(p, 4));
      p = _mm_add_epi16(p, _mm_slli_si128(p, 8));
      const __m128i low = _mm_add_epi32(_mm_cvtepu16_epi32(p), carry);
      const __m128i high = _mm_add_epi32(_mm_cvtepu16_epi32(_mm_srli_si128(p, 8)), carry);
      carry = _mm_shuffle_epi32(high, 0xFF);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x + 1),
                       _mm_add_epi32(low, load(above + x + 1)));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x + 5),
                       _mm_add_epi32(high, load(above + x + 5)));
    }
    row_sum = static_cast<std::uint32_t>(_mm_cvtsi128_si32(carry));
  }
  for (; x < width; ++x) {
    row_sum += pixels[x];
    out[x + 1] = above[x + 1] + row_sum;
  }
}

AIEF_SIMD_NAMESPACE_END

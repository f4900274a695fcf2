#pragma once
// The register layer of one integral image row (simd/integral_image_row/portable.hpp) on x86:
// SSE4.2 takes 8 pixels a step in one 128-bit register; AVX2 and AVX-512 take 16, the two 128-bit
// lanes' prefix sums by shifts within each lane and the low lane's total broadcast into the high
// lane.
#include <immintrin.h>

#include <cstdint>
#include <type_traits>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace integral_image_row_detail {

// The register the kernel runs on: 128-bit (SSE4.2) or 256-bit (AVX2 and AVX-512). Templates on
// Arch, so every instruction set's copy is its own symbol.
template <class Arch, int kBits = std::is_base_of_v<xsimd::avx2, Arch> ? 256 : 128>
struct Registers;

template <class Arch>
struct Registers<Arch, 128> {
  static constexpr int kPixels = 8;
  using Carry = __m128i;

  static std::uint32_t row_sum(Carry carry) {
    return static_cast<std::uint32_t>(_mm_cvtsi128_si32(carry));
  }

  // Entries out[0, 8) from pixels[0, 8) and above[0, 8); returns the new carry.
  static Carry step(const std::uint8_t* pixels, const std::uint32_t* above, std::uint32_t* out,
                    Carry carry) {
    __m128i p = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(pixels)));
    p = _mm_add_epi16(p, _mm_slli_si128(p, 2));
    p = _mm_add_epi16(p, _mm_slli_si128(p, 4));
    p = _mm_add_epi16(p, _mm_slli_si128(p, 8));
    const __m128i low = _mm_add_epi32(_mm_cvtepu16_epi32(p), carry);
    const __m128i high = _mm_add_epi32(_mm_cvtepu16_epi32(_mm_srli_si128(p, 8)), carry);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_add_epi32(low, load16<Arch>(above)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4),
                     _mm_add_epi32(high, load16<Arch>(above + 4)));
    return _mm_shuffle_epi32(high, 0xFF);
  }
};

// The 128-bit form's contract for 16 entries a step.
template <class Arch>
struct Registers<Arch, 256> {
  static constexpr int kPixels = 16;
  using Carry = __m256i;
  static Carry step(const std::uint8_t* pixels, const std::uint32_t* above, std::uint32_t* out,
                    Carry carry) {
    __m256i p = _mm256_cvtepu8_epi16(load16<Arch>(pixels));
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
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                        _mm256_add_epi32(low, load32<Arch>(above)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 8),
                        _mm256_add_epi32(high, load32<Arch>(above + 8)));
    return _mm256_permutevar8x32_epi32(high, _mm256_set1_epi32(7));
  }
  static std::uint32_t row_sum(Carry carry) {
    return static_cast<std::uint32_t>(_mm256_cvtsi256_si32(carry));
  }
};

}  // namespace integral_image_row_detail

AIEF_SIMD_NAMESPACE_END

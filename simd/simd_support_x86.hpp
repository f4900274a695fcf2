#pragma once
// lane_bits and any_nonzero (simd/simd_support.hpp) for SSE4.2, AVX2 and AVX-512BW.
#include <cstdint>
#include <type_traits>

#include <immintrin.h>

#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

template <class Arch>
inline std::uint64_t lane_bits(const xsimd::batch_bool<std::uint8_t, Arch>& b) {
  if constexpr (std::is_base_of_v<xsimd::avx512bw, Arch>) {
    return static_cast<std::uint64_t>(static_cast<__mmask64>(b));
  } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    return static_cast<std::uint32_t>(_mm256_movemask_epi8(static_cast<__m256i>(b)));
  } else {
    return static_cast<std::uint32_t>(_mm_movemask_epi8(static_cast<__m128i>(b)));
  }
}

// One vptest (SSE4.1, AVX2) or vptestmb (AVX-512BW).
template <class Arch>
inline bool any_nonzero(const U8<Arch>& v) {
  if constexpr (std::is_base_of_v<xsimd::avx512bw, Arch>) {
    const __m512i x = v;
    return _mm512_test_epi8_mask(x, x) != 0;
  } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    const __m256i x = v;
    return !_mm256_testz_si256(x, x);
  } else {
    const __m128i x = v;
    return !_mm_testz_si128(x, x);
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

#pragma once
// lane_bits and any_nonzero (simd/simd_support.hpp) for SSE4.2, AVX2 and AVX-512BW, and the
// unaligned loads the intrinsics kernels share.
#include <cstdint>
#include <type_traits>

#include <immintrin.h>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

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

// Each byte's count of set bits (0..8), by a nibble table (vpshufb): the AVX2 popcount of the
// Hamming kernels.
template <class Arch>
inline __m256i byte_popcounts(__m256i x) {
  const __m256i table = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2,
                                         1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
  const __m256i low_nibble = _mm256_set1_epi8(0x0f);
  return _mm256_add_epi8(
      _mm256_shuffle_epi8(table, _mm256_and_si256(x, low_nibble)),
      _mm256_shuffle_epi8(table, _mm256_and_si256(_mm256_srli_epi16(x, 4), low_nibble)));
}

// Unaligned 16- and 32-byte loads from any pointer. Arch only keeps each instruction set's copy
// its own symbol.
template <class Arch>
inline __m128i load16(const void* p) {
  return _mm_loadu_si128(static_cast<const __m128i*>(p));
}
template <class Arch>
inline __m256i load32(const void* p) {
  return _mm256_loadu_si256(static_cast<const __m256i*>(p));
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// Hamming distances of one 256-bit descriptor to many: XOR, byte popcount by a nibble table
// (vpshufb), horizontal sums by vpsadbw. One descriptor per AVX2 register, two per AVX-512 one.
// SSE4.2 uses the popcnt instruction on 64-bit words.
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void hamming_256_many(const std::uint8_t* query, const std::uint8_t* train, int n_train,
                      std::uint16_t* distances) {
  if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    const __m256i q = load32<Arch>(query);
    for (int j = 0; j < n_train; ++j) {
      const __m256i counts =
          byte_popcounts<Arch>(_mm256_xor_si256(q, load32<Arch>(train + 32 * j)));
      const __m256i sums =
          _mm256_sad_epu8(counts, _mm256_setzero_si256());  // four 64-bit partial sums
      const __m128i half =
          _mm_add_epi64(_mm256_castsi256_si128(sums), _mm256_extracti128_si256(sums, 1));
      distances[j] =
          static_cast<std::uint16_t>(_mm_cvtsi128_si64(half) + _mm_extract_epi64(half, 1));
    }
  } else {
    std::uint64_t q[4];
    std::memcpy(q, query, 32);
    for (int j = 0; j < n_train; ++j) {
      std::uint64_t t[4];
      std::memcpy(t, train + 32 * j, 32);
      distances[j] = static_cast<std::uint16_t>(
          __builtin_popcountll(q[0] ^ t[0]) + __builtin_popcountll(q[1] ^ t[1]) +
          __builtin_popcountll(q[2] ^ t[2]) + __builtin_popcountll(q[3] ^ t[3]));
    }
  }
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// positions_within_bounds (core/kernels/positions_within_bounds.hpp) 32 distances per step: a
// signed 16-bit max of the bounds, one compare, a lane mask, then only the (few) set bits are
// walked. The tail runs the scalar loop. x86 only: the NEON table keeps the scalar filter.
#include <algorithm>
#include <cstdint>
#include <type_traits>

#include <immintrin.h>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
int positions_within_bounds(const std::uint16_t* distances, const std::int16_t* train_bounds, int n,
                            int query_bound, std::int32_t* positions) {
  int count = 0;
  int k = 0;
  const auto walk = [&](std::uint32_t within, int base) {
    for (; within != 0; within &= within - 1) positions[count++] = base + __builtin_ctz(within);
  };
  if constexpr (std::is_base_of_v<xsimd::avx512bw, Arch>) {
    const __m512i query = _mm512_set1_epi16(static_cast<short>(query_bound));
    for (; k + 32 <= n; k += 32) {
      const __m512i bound = _mm512_max_epi16(_mm512_loadu_si512(train_bounds + k), query);
      walk(_mm512_cmple_epi16_mask(_mm512_loadu_si512(distances + k), bound), k);
    }
  } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    const __m256i query = _mm256_set1_epi16(static_cast<short>(query_bound));
    for (; k + 32 <= n; k += 32) {
      const auto above = [&](int at) {
        const __m256i bound = _mm256_max_epi16(
            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(train_bounds + at)), query);
        return _mm256_cmpgt_epi16(
            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(distances + at)), bound);
      };
      // packs interleaves the two halves per 128-bit lane; the permute restores position order.
      const __m256i packed =
          _mm256_permute4x64_epi64(_mm256_packs_epi16(above(k), above(k + 16)), 0xD8);
      walk(~static_cast<std::uint32_t>(_mm256_movemask_epi8(packed)), k);
    }
  }
  for (; k < n; ++k) {
    positions[count] = k;
    count += static_cast<std::int16_t>(distances[k]) <= std::max<int>(query_bound, train_bounds[k]);
  }
  return count;
}

AIEF_SIMD_NAMESPACE_END

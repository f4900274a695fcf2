#pragma once
// The Hamming kernel of the sweep matcher (core/kernels/hamming_256_blocked.hpp) with AVX-512
// VPOPCNTDQ: one popcount per 32-bit lane, 16 trains a vector. Included by the one unit compiled
// with -mavx512vpopcntdq, simd/kernels_avx512vpopcntdq.cpp.
#include <cstdint>
#include <cstring>

#include <immintrin.h>

#include "core/kernels/hamming_256_blocked.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

// One block (16 trains) per iteration: 8 loads, XORs, popcounts and adds, one narrowing store.
inline void hamming_256_blocked_vpopcntdq(const std::uint8_t* query, const std::uint32_t* blocked,
                                          int n_blocks, std::uint16_t* distances) {
  __m512i q[kDescriptorWords];
  for (int w = 0; w < kDescriptorWords; ++w) {
    std::uint32_t word;
    std::memcpy(&word, query + 4 * w, 4);
    q[w] = _mm512_set1_epi32(static_cast<int>(word));
  }
  for (int block = 0; block < n_blocks; ++block) {
    const std::uint32_t* words = block_words(blocked, block);
    __m512i sum = _mm512_popcnt_epi32(_mm512_xor_si512(q[0], _mm512_loadu_si512(words)));
    for (int w = 1; w < kDescriptorWords; ++w)
      sum = _mm512_add_epi32(sum, _mm512_popcnt_epi32(_mm512_xor_si512(
                                      q[w], _mm512_loadu_si512(words + w * kHammingBlock))));
    _mm512_mask_cvtepi32_storeu_epi16(distances + block * kHammingBlock, 0xffff,
                                      sum);  // vpmovdw to memory
  }
}

AIEF_SIMD_NAMESPACE_END

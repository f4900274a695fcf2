#pragma once
// Hamming distances of one descriptor to 16 transposed ones per step
// (core/kernels/hamming_256_blocked.hpp): each 32-bit lane holds the same word of a different
// train, so the query word is broadcast, XORed and popcounted lane-wise and the eight words' counts
// are added lane-wise, with no horizontal sum per train. AVX2 counts bits by a nibble table
// (vpshufb) and sums the four byte counts of a lane with vpmaddubsw + vpmaddwd; AVX-512 with
// VPOPCNTDQ counts a lane in one instruction (simd/hamming_256_blocked/x86_avx512vpopcntdq.hpp).
// SSE4.2 runs the scalar loop, two words per 64-bit popcnt.
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/kernels/hamming_256_blocked.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void hamming_256_blocked(const std::uint8_t* query, const std::uint32_t* blocked, int n_blocks,
                         std::uint16_t* distances) {
  if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    const __m256i ones_u8 = _mm256_set1_epi8(1);
    const __m256i ones_i16 = _mm256_set1_epi16(1);
    __m256i q[kDescriptorWords];
    for (int w = 0; w < kDescriptorWords; ++w) {
      std::uint32_t word;
      std::memcpy(&word, query + 4 * w, 4);
      q[w] = _mm256_set1_epi32(static_cast<int>(word));
    }
    // The 8 trains of one half block: byte counts summed over the eight words (<= 64 per byte),
    // then the four bytes of each lane summed.
    const auto half_block = [&](const std::uint32_t* words) {
      __m256i bytes = _mm256_setzero_si256();
      for (int w = 0; w < kDescriptorWords; ++w) {
        bytes = _mm256_add_epi8(bytes, byte_popcounts<Arch>(_mm256_xor_si256(
                                           q[w], load32<Arch>(words + w * kHammingBlock))));
      }
      return _mm256_madd_epi16(_mm256_maddubs_epi16(bytes, ones_u8), ones_i16);
    };
    for (int block = 0; block < n_blocks; ++block) {
      const std::uint32_t* words = block_words(blocked, block);
      // packus interleaves the halves per 128-bit lane; the permute puts trains 0..15 in order.
      const __m256i packed = _mm256_packus_epi32(half_block(words), half_block(words + 8));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(distances + block * kHammingBlock),
                          _mm256_permute4x64_epi64(packed, 0xD8));
    }
  } else {
    std::uint32_t q[kDescriptorWords];
    std::memcpy(q, query, 32);
    for (int block = 0; block < n_blocks; ++block) {
      const std::uint32_t* words = block_words(blocked, block);
      for (int lane = 0; lane < kHammingBlock; ++lane) {
        int distance = 0;  // two words per 64-bit popcnt
        for (int w = 0; w < kDescriptorWords; w += 2)
          distance += __builtin_popcountll(
              (static_cast<std::uint64_t>(q[w] ^ words[w * kHammingBlock + lane]) << 32) |
              (q[w + 1] ^ words[(w + 1) * kHammingBlock + lane]));
        distances[block * kHammingBlock + lane] = static_cast<std::uint16_t>(distance);
      }
    }
  }
}

AIEF_SIMD_NAMESPACE_END

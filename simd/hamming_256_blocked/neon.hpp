#pragma once
// hamming_256_blocked (core/kernels/hamming_256_blocked.hpp) on AArch64 NEON: a block of 16 trains
// is four registers of four 32-bit lanes per word. XOR with the broadcast query word, byte popcount
// (cnt), byte counts summed over the eight words (<= 64), then the four bytes of each lane by
// two pairwise widening adds.
#include <cstdint>
#include <cstring>

#include <arm_neon.h>

#include "core/kernels/hamming_256_blocked.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void hamming_256_blocked(const std::uint8_t* query, const std::uint32_t* blocked, int n_blocks,
                         std::uint16_t* distances) {
  uint32x4_t q[kDescriptorWords];
  for (int w = 0; w < kDescriptorWords; ++w) {
    std::uint32_t word;
    std::memcpy(&word, query + 4 * w, 4);
    q[w] = vdupq_n_u32(word);
  }
  for (int block = 0; block < n_blocks; ++block) {
    const std::uint32_t* words = block_words(blocked, block);
    std::uint16_t* out = distances + block * kHammingBlock;
    for (int quarter = 0; quarter < 4; ++quarter) {
      uint8x16_t bytes = vdupq_n_u8(0);
      for (int w = 0; w < kDescriptorWords; ++w)
        bytes = vaddq_u8(bytes, vcntq_u8(vreinterpretq_u8_u32(veorq_u32(
                                    q[w], vld1q_u32(words + w * kHammingBlock + 4 * quarter)))));
      vst1_u16(out + 4 * quarter, vmovn_u32(vpaddlq_u16(vpaddlq_u8(bytes))));
    }
  }
}

AIEF_SIMD_NAMESPACE_END

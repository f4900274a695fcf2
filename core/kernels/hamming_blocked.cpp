#include "core/kernels/hamming_blocked.hpp"

#include <bit>
#include <cstring>

namespace aief {

void block_descriptors(const std::uint8_t* descriptors, int n,
                       std::vector<std::uint32_t>& blocked) {
  const int blocks = hamming_block_count(n);
  blocked.assign(static_cast<std::size_t>(blocks) * kHammingBlock * kDescriptorWords, 0u);
  for (int k = 0; k < n; ++k) {
    std::uint32_t words[kDescriptorWords];
    std::memcpy(words, descriptors + static_cast<std::ptrdiff_t>(k) * 32, 32);
    const int block = k / kHammingBlock, lane = k % kHammingBlock;
    for (int w = 0; w < kDescriptorWords; ++w)
      blocked[static_cast<std::size_t>((block * kDescriptorWords + w) * kHammingBlock + lane)] =
          words[w];
  }
}

void hamming_256_blocked_scalar(const std::uint8_t* query, const std::uint32_t* blocked,
                                int n_blocks, std::uint16_t* distances) {
  std::uint32_t q[kDescriptorWords];
  std::memcpy(q, query, 32);
  for (int block = 0; block < n_blocks; ++block) {
    const std::uint32_t* words =
        blocked + static_cast<std::ptrdiff_t>(block) * kDescriptorWords * kHammingBlock;
    for (int lane = 0; lane < kHammingBlock; ++lane) {
      int distance = 0;
      for (int w = 0; w < kDescriptorWords; ++w)
        distance += std::popcount(q[w] ^ words[w * kHammingBlock + lane]);
      distances[block * kHammingBlock + lane] = static_cast<std::uint16_t>(distance);
    }
  }
}

}  // namespace aief

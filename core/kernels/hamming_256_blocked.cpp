#include "core/kernels/hamming_256_blocked.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

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

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

// The image's bytes as descriptors, blocked; the query is each of the first few descriptors.
std::string check_hamming_256_blocked(const KernelTable& scalar, const KernelTable& other,
                                      const GrayImage& src) {
  const int n = std::min(src.width() * src.height() / 32, 300);
  if (n < 1) return "";
  std::vector<std::uint32_t> blocked;
  block_descriptors(src.data(), n, blocked);
  const int blocks = hamming_block_count(n);
  std::vector<std::uint16_t> a(static_cast<std::size_t>(blocks * kHammingBlock)), b(a.size());
  for (int query = 0; query < std::min(n, 5); ++query) {
    for (int count : {blocks, blocks - 1, 1}) {
      if (count < 1) continue;
      std::fill(a.begin(), a.end(), 0xffff);
      std::fill(b.begin(), b.end(), 0xffff);
      scalar.hamming_256_blocked(src.data() + 32 * query, blocked.data(), count, a.data());
      other.hamming_256_blocked(src.data() + 32 * query, blocked.data(), count, b.data());
      const std::string diff = first_difference(a, b, other.name, "distance to train");
      if (!diff.empty()) return where(src, "query " + std::to_string(query) + ", " + diff);
    }
  }
  return "";
}

// Every sample descriptor against all (at most 512) in the sweep matcher's layout.
KernelWorkload workload_hamming_256_blocked(const KernelBenchInputs& in, const KernelTable& k) {
  const int n = std::min(static_cast<int>(in.points.size()), 512);
  std::vector<std::uint32_t> blocked;
  block_descriptors(in.descriptors.data(), n, blocked);
  const int blocks = hamming_block_count(n);
  return {[&in, &k, n, blocks, blocked = std::move(blocked),
           distances = std::vector<std::uint16_t>(
               static_cast<std::size_t>(blocks * kHammingBlock))]() mutable {
            for (int i = 0; i < n; ++i)
              k.hamming_256_blocked(in.descriptors.data() + 32 * i, blocked.data(), blocks,
                                    distances.data());
          },
          static_cast<long long>(n) * n};
}

}  // namespace aief

#pragma once
// Hamming distances of one 256-bit descriptor to many, with the many stored transposed in blocks
// of 16 (the sweep's matcher, core/sweep/sweep_matcher.cpp). Word w (bytes 4w..4w+3, as a
// little-endian uint32) of descriptor 16 g + t sits at blocked[(8 g + w) * 16 + t]: a vector kernel
// compares the query with 16 trains per step (a broadcast query word, one XOR and one popcount per
// word) and needs no horizontal sum per train.
#include <cstdint>
#include <vector>

namespace aief {

constexpr int kHammingBlock = 16;    // descriptors per block
constexpr int kDescriptorWords = 8;  // 32-bit words per 256-bit descriptor

// Blocks needed for n descriptors.
inline int hamming_block_count(int n) { return (n + kHammingBlock - 1) / kHammingBlock; }

// Writes n descriptors of 32 bytes into the blocked layout, the last block padded with zero
// descriptors; `blocked` is resized to hamming_block_count(n) * 16 * 8 words.
void block_descriptors(const std::uint8_t* descriptors, int n, std::vector<std::uint32_t>& blocked);

// distances[k] = hamming(query, descriptor k of `blocked`) for k in [0, 16 n_blocks): padding
// descriptors give the query's own popcount. Reads 16 * 8 * n_blocks words.
void hamming_256_blocked_scalar(const std::uint8_t* query, const std::uint32_t* blocked,
                                int n_blocks, std::uint16_t* distances);

}  // namespace aief

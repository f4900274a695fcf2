#pragma once
// Hamming distance between 256-bit descriptors, for matching (docs/design.md §9).
#include <cstdint>

namespace aief {

std::uint32_t hamming_256_scalar(const std::uint8_t* a, const std::uint8_t* b);

// distances[j] = hamming(query, train + 32 * j) for j in [0, n_train).
void hamming_256_many_scalar(const std::uint8_t* query, const std::uint8_t* train, int n_train,
                             std::uint16_t* distances);

}  // namespace aief

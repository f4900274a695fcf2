#include "core/kernels/hamming.hpp"

#include <bit>
#include <cstring>

namespace aief {

std::uint32_t hamming_256_scalar(const std::uint8_t* a, const std::uint8_t* b) {
  std::uint32_t distance = 0;
  for (int word = 0; word < 4; ++word) {
    std::uint64_t x, y;
    std::memcpy(&x, a + 8 * word, 8);
    std::memcpy(&y, b + 8 * word, 8);
    distance += static_cast<std::uint32_t>(std::popcount(x ^ y));
  }
  return distance;
}

void hamming_256_many_scalar(const std::uint8_t* query, const std::uint8_t* train, int n_train,
                             std::uint16_t* distances) {
  for (int j = 0; j < n_train; ++j)
    distances[j] = static_cast<std::uint16_t>(
        hamming_256_scalar(query, train + static_cast<std::ptrdiff_t>(j) * 32));
}

}  // namespace aief

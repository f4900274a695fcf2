#include "core/kernels/hamming_256_many.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

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

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_hamming_256_many(const KernelTable& scalar, const KernelTable& other,
                                   const GrayImage& src) {
  const int n = std::min(src.width() * src.height() / 32, 300);
  if (n < 1) return "";
  const std::uint8_t* train = src.data();
  std::vector<std::uint16_t> a(static_cast<std::size_t>(n)), b(a.size());
  for (int count : {n, std::max(0, n - 1), std::min(n, 1)}) {
    scalar.hamming_256_many(train, train, count, a.data());
    other.hamming_256_many(train, train, count, b.data());
    a.resize(static_cast<std::size_t>(count));
    b.resize(static_cast<std::size_t>(count));
    const std::string diff = first_difference(a, b, other.name, "distance");
    if (!diff.empty()) return where(src, diff);
    a.resize(static_cast<std::size_t>(n));
    b.resize(static_cast<std::size_t>(n));
  }
  return "";
}

// Every sample descriptor against all (at most 512), as brute-force matching does.
KernelWorkload workload_hamming_256_many(const KernelBenchInputs& in, const KernelTable& k) {
  const int n = std::min(static_cast<int>(in.points.size()), 512);
  return {
      [&in, &k, n, distances = std::vector<std::uint16_t>(static_cast<std::size_t>(n))]() mutable {
        for (int i = 0; i < n; ++i)
          k.hamming_256_many(in.descriptors.data() + 32 * i, in.descriptors.data(), n,
                             distances.data());
      },
      static_cast<long long>(n) * n};
}

}  // namespace aief

// Hamming distance of 256-bit descriptors against a bit-by-bit count; the many-train form
// equal to the single one, at any byte alignment; the blocked (transposed) form and the sweep
// matcher's bound filter against their definitions.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/kernels/hamming_256_blocked.hpp"
#include "core/kernels/hamming_256_many.hpp"
#include "core/kernels/positions_within_bounds.hpp"

namespace aief {
namespace {

std::uint32_t hamming_bit_by_bit(const std::uint8_t* a, const std::uint8_t* b) {
  std::uint32_t distance = 0;
  for (int bit = 0; bit < 256; ++bit)
    distance += ((a[bit / 8] >> (bit % 8)) & 1) != ((b[bit / 8] >> (bit % 8)) & 1);
  return distance;
}

std::vector<std::uint8_t> random_bytes(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> bytes(n);
  for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(rng));
  return bytes;
}

TEST(Hamming, ExtremesAndSingleBits) {
  std::vector<std::uint8_t> zeros(32, 0), ones(32, 0xff);
  EXPECT_EQ(hamming_256_scalar(zeros.data(), zeros.data()), 0u);
  EXPECT_EQ(hamming_256_scalar(zeros.data(), ones.data()), 256u);
  for (int bit = 0; bit < 256; ++bit) {
    std::vector<std::uint8_t> one = zeros;
    one[static_cast<std::size_t>(bit / 8)] = static_cast<std::uint8_t>(1 << (bit % 8));
    EXPECT_EQ(hamming_256_scalar(zeros.data(), one.data()), 1u) << "bit " << bit;
    EXPECT_EQ(hamming_256_scalar(one.data(), ones.data()), 255u) << "bit " << bit;
  }
}

TEST(Hamming, EqualsTheBitByBitCountOnRandomDescriptors) {
  // One spare byte on each side so the descriptors can start at every alignment.
  const std::vector<std::uint8_t> bytes = random_bytes(2000 * 32 + 8, 17);
  for (int i = 0; i + 1 < 2000; ++i) {
    const std::uint8_t* a = bytes.data() + i * 32 + i % 8;
    const std::uint8_t* b = bytes.data() + (i + 1) * 32;
    ASSERT_EQ(hamming_256_scalar(a, b), hamming_bit_by_bit(a, b)) << "pair " << i;
  }
}

TEST(Hamming, ManyEqualsSingle) {
  const std::vector<std::uint8_t> train = random_bytes(513 * 32 + 1, 23);
  const std::vector<std::uint8_t> queries = random_bytes(4 * 32 + 3, 29);
  for (int q = 0; q < 4; ++q)
    for (int offset : {0, 1}) {
      const std::uint8_t* query = queries.data() + q * 32 + (q % 4);
      const std::uint8_t* base = train.data() + offset;
      for (int n : {0, 1, 7, 513}) {
        std::vector<std::uint16_t> distances(static_cast<std::size_t>(n) + 1, 0xffff);
        hamming_256_many_scalar(query, base, n, distances.data());
        for (int j = 0; j < n; ++j)
          ASSERT_EQ(distances[static_cast<std::size_t>(j)],
                    hamming_bit_by_bit(query, base + j * 32))
              << "query " << q << ", train " << j << " of " << n;
        EXPECT_EQ(distances[static_cast<std::size_t>(n)], 0xffff)
            << "wrote past " << n << " distances";
      }
    }
}

TEST(Hamming, BlockedEqualsTheBitByBitCountAndPadsWithZeroDescriptors) {
  const std::vector<std::uint8_t> train = random_bytes(70 * 32, 31);
  const std::vector<std::uint8_t> query = random_bytes(32, 37);
  const std::vector<std::uint8_t> zeros(32, 0);
  for (int n : {1, 15, 16, 17, 70}) {
    std::vector<std::uint32_t> blocked;
    block_descriptors(train.data(), n, blocked);
    const int blocks = hamming_block_count(n);
    ASSERT_EQ(blocked.size(), static_cast<std::size_t>(blocks * kHammingBlock * kDescriptorWords));
    std::vector<std::uint16_t> distances(static_cast<std::size_t>(blocks * kHammingBlock) + 1,
                                         0xffff);
    hamming_256_blocked_scalar(query.data(), blocked.data(), blocks, distances.data());
    for (int j = 0; j < blocks * kHammingBlock; ++j) {
      const std::uint8_t* expected_train = j < n ? train.data() + j * 32 : zeros.data();
      ASSERT_EQ(distances[static_cast<std::size_t>(j)],
                hamming_bit_by_bit(query.data(), expected_train))
          << "train " << j << " of " << n;
    }
    EXPECT_EQ(distances.back(), 0xffff) << "wrote past " << blocks << " blocks";
  }
}

TEST(BoundFilter, KeepsExactlyThePositionsWithinEitherBound) {
  std::mt19937 rng(41);
  std::uniform_int_distribution<int> distance(0, 256), bound(-1, 256);
  for (int n : {0, 1, 31, 32, 33, 100}) {
    std::vector<std::uint16_t> distances(static_cast<std::size_t>(n));
    std::vector<std::int16_t> bounds(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      distances[static_cast<std::size_t>(k)] =
          static_cast<std::uint16_t>(k % 9 == 0 ? 0x7fff : distance(rng));  // 0x7fff: excluded
      bounds[static_cast<std::size_t>(k)] = static_cast<std::int16_t>(bound(rng));
    }
    for (int query_bound : {-1, 0, 100, 256}) {
      std::vector<std::int32_t> positions(static_cast<std::size_t>(n));
      positions.resize(static_cast<std::size_t>(positions_within_bounds_scalar(
          distances.data(), bounds.data(), n, query_bound, positions.data())));
      std::vector<std::int32_t> expected;
      for (int k = 0; k < n; ++k) {
        const int d = distances[static_cast<std::size_t>(k)];
        if (d != 0x7fff && (d <= query_bound || d <= bounds[static_cast<std::size_t>(k)]))
          expected.push_back(k);
      }
      EXPECT_EQ(positions, expected) << "n " << n << ", query bound " << query_bound;
    }
  }
}

}  // namespace
}  // namespace aief

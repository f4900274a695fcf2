#include "core/kernels/positions_within_bounds.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

int positions_within_bounds_scalar(const std::uint16_t* distances, const std::int16_t* train_bounds,
                                   int n, int query_bound, std::int32_t* positions) {
  int count = 0;
  for (int k = 0; k < n; ++k) {
    positions[count] = k;  // written always, kept when it passes: no branch on the data
    count += static_cast<std::int16_t>(distances[k]) <= std::max<int>(query_bound, train_bounds[k]);
  }
  return count;
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

// Distances and bounds made from the image's bytes: distances in 0..256 plus the excluded value
// 0x7fff, bounds in -1..256, at every query bound the matcher uses (-1 none, 256 all).
std::string check_positions_within_bounds(const KernelTable& scalar, const KernelTable& other,
                                          const GrayImage& src) {
  const int n = src.width() * src.height();
  if (n < 1) return "";
  std::vector<std::uint16_t> distances(static_cast<std::size_t>(n));
  std::vector<std::int16_t> bounds(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const int v = src.data()[k], u = src.data()[(k * 7 + 3) % n];
    distances[static_cast<std::size_t>(k)] =
        static_cast<std::uint16_t>(v == 255 ? 0x7fff : v + (u & 1));
    bounds[static_cast<std::size_t>(k)] = static_cast<std::int16_t>(u == 0     ? -1
                                                                    : u == 255 ? 256
                                                                               : u);
  }
  std::vector<std::int32_t> a(static_cast<std::size_t>(n)), b(a.size());
  for (int query_bound : {-1, 0, 60, 128, 200, 256}) {
    for (int count : {n, n - 1, std::min(n, 33)}) {
      a.resize(static_cast<std::size_t>(scalar.positions_within_bounds(
          distances.data(), bounds.data(), count, query_bound, a.data())));
      b.resize(static_cast<std::size_t>(other.positions_within_bounds(
          distances.data(), bounds.data(), count, query_bound, b.data())));
      const std::string diff = first_difference(a, b, other.name, "position within bounds");
      if (!diff.empty())
        return where(src, "query bound " + std::to_string(query_bound) + ", " + diff);
      a.resize(static_cast<std::size_t>(n));
      b.resize(static_cast<std::size_t>(n));
    }
  }
  return "";
}

// The sweep matcher's filter over each query's distances to every train descriptor (at most 512
// sample descriptors): the trains within the larger of the two bounds, here 64 bits on both sides.
KernelWorkload workload_positions_within_bounds(const KernelBenchInputs& in, const KernelTable& k) {
  const int n = std::min(static_cast<int>(in.points.size()), 512);
  std::vector<std::uint16_t> distances(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    hamming_256_many_scalar(in.descriptors.data() + 32 * i, in.descriptors.data(), n,
                            distances.data() + static_cast<std::ptrdiff_t>(i) * n);
  return {[&k, n, distances = std::move(distances),
           train_bounds = std::vector<std::int16_t>(static_cast<std::size_t>(n), 64),
           positions = std::vector<std::int32_t>(static_cast<std::size_t>(n))]() mutable {
            for (int i = 0; i < n; ++i)
              k.positions_within_bounds(distances.data() + static_cast<std::ptrdiff_t>(i) * n,
                                        train_bounds.data(), n, 64, positions.data());
          },
          static_cast<long long>(n) * n};
}

}  // namespace aief

#include "core/sweep/sweep_runs.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace aief {

std::vector<int> balanced_runs(const std::vector<double>& fresh,
                               const std::vector<double>& incremental, int runs) {
  const int n = static_cast<int>(fresh.size());
  assert(incremental.size() == fresh.size() && runs >= 1 && runs <= n);
  // prefix[k]: incremental[0] + ... + incremental[k - 1], so a run [j, k) costs
  // fresh[j] + prefix[k] - prefix[j + 1].
  std::vector<double> prefix(static_cast<std::size_t>(n) + 1, 0.0);
  for (int k = 0; k < n; ++k)
    prefix[static_cast<std::size_t>(k) + 1] =
        prefix[static_cast<std::size_t>(k)] + incremental[static_cast<std::size_t>(k)];
  const auto cost = [&](int j, int k) {
    return fresh[static_cast<std::size_t>(j)] + prefix[static_cast<std::size_t>(k)] -
           prefix[static_cast<std::size_t>(j) + 1];
  };
  // largest[r][k]: the smallest largest cost of cutting [0, k) into r runs; cut[r][k] the start of
  // the last of them. A sweep has a few dozen thresholds: the plain dynamic programme will do.
  const double infinity = std::numeric_limits<double>::infinity();
  const std::size_t columns = static_cast<std::size_t>(n) + 1;
  std::vector<double> largest((static_cast<std::size_t>(runs) + 1) * columns, infinity);
  std::vector<int> cut((static_cast<std::size_t>(runs) + 1) * columns, 0);
  const auto at = [&](int r, int k) {
    return static_cast<std::size_t>(r) * columns + static_cast<std::size_t>(k);
  };
  largest[at(0, 0)] = 0;
  for (int r = 1; r <= runs; ++r)
    for (int k = r; k <= n; ++k)
      for (int j = r - 1; j < k; ++j) {
        const double candidate = std::max(largest[at(r - 1, j)], cost(j, k));
        if (candidate < largest[at(r, k)]) {
          largest[at(r, k)] = candidate;
          cut[at(r, k)] = j;
        }
      }
  std::vector<int> begin(static_cast<std::size_t>(runs) + 1);
  begin[static_cast<std::size_t>(runs)] = n;
  for (int r = runs; r >= 1; --r)
    begin[static_cast<std::size_t>(r) - 1] = cut[at(r, begin[static_cast<std::size_t>(r)])];
  return begin;
}

}  // namespace aief

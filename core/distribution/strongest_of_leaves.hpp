#pragma once
// The last step of both quadtrees (core/distribution/distribution.cpp, ORB-SLAM's;
// core/distribution/quadtree_weighted.cpp): each leaf keeps its strongest candidate.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"

namespace aief {

// Appends to `selected` the strongest candidate (stronger()) of each alive node's
// keys[begin, end); a last split's overshoot of n_wanted (up to 3) drops the weakest of them.
template <class Node>
void keep_strongest_of_leaves(const std::vector<Node>& nodes, const std::vector<std::int32_t>& keys,
                              const std::vector<Candidate>& candidates, int n_wanted,
                              std::vector<std::int32_t>& selected) {
  const auto candidate = [&](std::int32_t key) -> const Candidate& {
    return candidates[static_cast<std::size_t>(key)];
  };
  const std::size_t first = selected.size();
  for (const Node& node : nodes) {
    if (!node.alive) continue;
    std::int32_t best = keys[static_cast<std::size_t>(node.begin)];
    for (std::int32_t k = node.begin + 1; k < node.end; ++k) {
      const std::int32_t key = keys[static_cast<std::size_t>(k)];
      if (stronger(candidate(key), candidate(best))) best = key;
    }
    selected.push_back(best);
  }
  if (selected.size() - first > static_cast<std::size_t>(n_wanted)) {
    std::sort(selected.begin() + static_cast<std::ptrdiff_t>(first), selected.end(),
              [&](std::int32_t a, std::int32_t b) { return stronger(candidate(a), candidate(b)); });
    selected.resize(first + static_cast<std::size_t>(n_wanted));
  }
}

}  // namespace aief

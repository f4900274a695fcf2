#include "core/distribution/quadtree_weighted.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <queue>

#include "core/distribution/strongest_of_leaves.hpp"

namespace aief {

std::int64_t entropy_weight(double entropy_bits) {
  return std::max<std::int64_t>(0, std::llround(entropy_bits * 256.0));
}

namespace {

struct WeightedNode {
  int x0, y0, x1, y1;       // relative to the tree's origin
  std::int32_t begin, end;  // its candidates: keys[begin, end)
  std::int64_t weight;      // sum of its candidates' weights
  bool alive;
  std::int32_t size() const { return end - begin; }
};

}  // namespace

void distribute_quadtree_weighted(const std::vector<Candidate>& candidates,
                                  const std::vector<std::int64_t>& weights, int min_x, int max_x,
                                  int min_y, int max_y, int n_wanted,
                                  std::vector<std::int32_t>& selected) {
  if (candidates.empty() || n_wanted <= 0) return;
  assert(weights.size() == candidates.size());
  const int width = max_x - min_x, height = max_y - min_y;
  assert(width > 0 && height > 0);

  std::vector<std::int32_t> keys(candidates.size());
  std::vector<WeightedNode> nodes;
  int alive = 0;

  // Initial nodes as distribute_quadtree's: side by side, about square, at least one.
  const int initial = std::max(
      1, static_cast<int>(std::lround(static_cast<float>(width) / static_cast<float>(height))));
  const float node_width = static_cast<float>(width) / static_cast<float>(initial);
  std::vector<std::int32_t> owner(candidates.size());
  std::vector<std::int32_t> starts(static_cast<std::size_t>(initial) + 1, 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const float x = static_cast<float>(candidates[i].x - min_x);
    owner[i] = std::min(initial - 1, static_cast<int>(x / node_width));
    ++starts[static_cast<std::size_t>(owner[i]) + 1];
  }
  for (int i = 0; i < initial; ++i)
    starts[static_cast<std::size_t>(i) + 1] += starts[static_cast<std::size_t>(i)];
  {
    std::vector<std::int32_t> cursor(starts.begin(), starts.end() - 1);
    for (std::size_t i = 0; i < candidates.size(); ++i)
      keys[static_cast<std::size_t>(cursor[static_cast<std::size_t>(owner[i])]++)] =
          static_cast<std::int32_t>(i);
  }
  const auto weight_of = [&](std::int32_t begin, std::int32_t end) {
    std::int64_t sum = 0;
    for (std::int32_t k = begin; k < end; ++k)
      sum += weights[static_cast<std::size_t>(keys[static_cast<std::size_t>(k)])];
    return sum;
  };
  for (int i = 0; i < initial; ++i) {
    const std::int32_t begin = starts[static_cast<std::size_t>(i)],
                       end = starts[static_cast<std::size_t>(i) + 1];
    if (begin == end) continue;
    const int x0 = static_cast<int>(node_width * static_cast<float>(i));
    const int x1 = static_cast<int>(node_width * static_cast<float>(i + 1));
    nodes.push_back({x0, 0, x1, height, begin, end, weight_of(begin, end), true});
    ++alive;
  }

  // The heap's top: the largest weight, then more candidates, then top-left first.
  const auto splits_later = [&](std::int32_t a, std::int32_t b) {
    const WeightedNode& na = nodes[static_cast<std::size_t>(a)];
    const WeightedNode& nb = nodes[static_cast<std::size_t>(b)];
    if (na.weight != nb.weight) return na.weight < nb.weight;
    if (na.size() != nb.size()) return na.size() < nb.size();
    if (na.y0 != nb.y0) return na.y0 > nb.y0;
    return na.x0 > nb.x0;
  };
  std::priority_queue<std::int32_t, std::vector<std::int32_t>, decltype(splits_later)> heap(
      splits_later);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].size() > 1) heap.push(static_cast<std::int32_t>(i));

  std::vector<std::int32_t> partition;
  while (alive < n_wanted && !heap.empty()) {
    const std::int32_t index = heap.top();
    heap.pop();
    const WeightedNode parent = nodes[static_cast<std::size_t>(index)];
    nodes[static_cast<std::size_t>(index)].alive = false;
    --alive;
    // ORB-SLAM2's DivideNode: halves rounded up; left when x < the split, up when y < it.
    const int split_x = parent.x0 + (parent.x1 - parent.x0 + 1) / 2;
    const int split_y = parent.y0 + (parent.y1 - parent.y0 + 1) / 2;
    std::int32_t counts[4] = {0, 0, 0, 0};
    partition.clear();
    for (std::int32_t k = parent.begin; k < parent.end; ++k) {
      const std::int32_t key = keys[static_cast<std::size_t>(k)];
      const Candidate& c = candidates[static_cast<std::size_t>(key)];
      const int q = (c.x - min_x < split_x ? 0 : 1) + (c.y - min_y < split_y ? 0 : 2);
      ++counts[q];
      partition.push_back(key * 4 + q);
    }
    std::int32_t cursor[4];
    cursor[0] = parent.begin;
    for (int q = 1; q < 4; ++q) cursor[q] = cursor[q - 1] + counts[q - 1];
    const std::int32_t first[4] = {cursor[0], cursor[1], cursor[2], cursor[3]};
    for (const std::int32_t tagged : partition)
      keys[static_cast<std::size_t>(cursor[tagged & 3]++)] = tagged >> 2;
    const int xs[3] = {parent.x0, split_x, parent.x1};
    const int ys[3] = {parent.y0, split_y, parent.y1};
    for (int q = 0; q < 4; ++q) {
      if (counts[q] == 0) continue;
      const int qx = q & 1, qy = q >> 1;
      const std::int32_t begin = first[q], end = first[q] + counts[q];
      nodes.push_back(
          {xs[qx], ys[qy], xs[qx + 1], ys[qy + 1], begin, end, weight_of(begin, end), true});
      ++alive;
      if (counts[q] > 1) heap.push(static_cast<std::int32_t>(nodes.size()) - 1);
    }
  }

  // The strongest candidate of each leaf; a last split's overshoot (up to 3) drops the weakest.
  keep_strongest_of_leaves(nodes, keys, candidates, n_wanted, selected);
}

}  // namespace aief

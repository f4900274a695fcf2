#include "core/distribution/distribution.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/distribution/strongest_of_leaves.hpp"

namespace aief {

namespace {

// Candidates kept per block when every block keeps min(R_i, k).
std::int64_t kept_at_level(const std::vector<BlockRange>& blocks, std::int32_t k) {
  std::int64_t sum = 0;
  for (const BlockRange& block : blocks) sum += std::min(block.size(), k);
  return sum;
}

}  // namespace

void distribute_proportional(const std::vector<Candidate>& candidates,
                             const std::vector<BlockRange>& blocks, int n_wanted,
                             std::vector<std::int32_t>& selected, DistributionScratch& scratch) {
  std::int64_t total = 0;
  std::int32_t largest = 0;
  for (const BlockRange& block : blocks) {
    total += block.size();
    largest = std::max(largest, block.size());
  }
  if (total <= n_wanted) {  // fewer candidates than wanted: every block keeps all of them
    for (const BlockRange& block : blocks)
      for (std::int32_t i = block.begin; i < block.end; ++i) selected.push_back(i);
    return;
  }

  // The water level k: the largest k with sum_i min(R_i, k) <= n_wanted (the fixed point of the
  // paper's "give k to each block, hand the rest to blocks that have more"). Binary search over
  // a monotone sum instead of the paper's iteration.
  std::int32_t lo = 0, hi = largest;
  while (lo < hi) {
    const std::int32_t mid = lo + (hi - lo + 1) / 2;
    if (kept_at_level(blocks, mid) <= n_wanted)
      lo = mid;
    else
      hi = mid - 1;
  }
  const std::int32_t k = lo;
  std::int64_t remainder = n_wanted - kept_at_level(blocks, k);

  // Within each block the strongest first; the (k+1)-th candidates of the fuller blocks compete
  // for the remainder.
  std::vector<std::int32_t>& order = scratch.order;
  std::vector<std::int32_t>& next_in_line = scratch.next_in_line;
  next_in_line.clear();
  const auto by_strength = [&](std::int32_t a, std::int32_t b) {
    return stronger(candidates[static_cast<std::size_t>(a)],
                    candidates[static_cast<std::size_t>(b)]);
  };
  for (const BlockRange& block : blocks) {
    const std::int32_t keep = std::min(block.size(), k);
    const std::int32_t ranked = std::min(block.size(), k + 1);
    order.resize(static_cast<std::size_t>(block.size()));
    for (std::int32_t i = 0; i < block.size(); ++i)
      order[static_cast<std::size_t>(i)] = block.begin + i;
    std::partial_sort(order.begin(), order.begin() + ranked, order.end(), by_strength);
    selected.insert(selected.end(), order.begin(), order.begin() + keep);
    if (ranked > keep) next_in_line.push_back(order[static_cast<std::size_t>(keep)]);
  }
  assert(remainder >= 0 && remainder < static_cast<std::int64_t>(next_in_line.size()) + 1);
  std::partial_sort(next_in_line.begin(), next_in_line.begin() + remainder, next_in_line.end(),
                    by_strength);
  selected.insert(selected.end(), next_in_line.begin(), next_in_line.begin() + remainder);
}

namespace {

using Node = QuadtreeNode;

class Quadtree {
 public:
  Quadtree(const std::vector<Candidate>& candidates, int min_x, int min_y,
           DistributionScratch& scratch)
      : keys(scratch.keys),
        nodes(scratch.nodes),
        candidates_(candidates),
        min_x_(min_x),
        min_y_(min_y),
        scratch_(scratch.partition) {
    keys.clear();
    nodes.clear();
  }

  std::vector<std::int32_t>& keys;  // candidate indices, grouped by node
  std::vector<Node>& nodes;         // every node ever made; `alive` marks the current leaves
  int alive_count = 0;

  void add(const Node& node) {
    nodes.push_back(node);
    ++alive_count;
  }

  // ORB-SLAM2's ExtractorNode::DivideNode: halves rounded up, a key goes left when x < the
  // split, up when y < the split. Appends the non-empty children; returns their node indices
  // through `children` (count returned).
  int divide(std::int32_t index, std::int32_t children[4]) {
    const Node parent = nodes[static_cast<std::size_t>(index)];
    nodes[static_cast<std::size_t>(index)].alive = false;
    --alive_count;
    const int half_x = (parent.x1 - parent.x0 + 1) / 2;
    const int half_y = (parent.y1 - parent.y0 + 1) / 2;
    const int split_x = parent.x0 + half_x, split_y = parent.y0 + half_y;

    // Stable partition of the parent's keys into the four quadrants, in place: each key's
    // quadrant is found once, kept in the two low bits of its scratch copy (keys < 2^29), then a
    // counting sort. Finding it twice, from the candidate each time, cost 40% more: orbslam2 mode
    // distributes every candidate of a level (callgrind, a 640x480 frame, AVX2: divide() 1.23 M
    // -> 0.88 M instructions, the frame 16.77 M -> 16.41 M).
    std::int32_t counts[4] = {0, 0, 0, 0};
    scratch_.resize(static_cast<std::size_t>(parent.end - parent.begin));
    const int split_x_abs = min_x_ + split_x, split_y_abs = min_y_ + split_y;
    for (std::int32_t k = parent.begin; k < parent.end; ++k) {
      const std::int32_t key = keys[static_cast<std::size_t>(k)];
      const Candidate& c = candidates_[static_cast<std::size_t>(key)];
      const int q = (c.x < split_x_abs ? 0 : 1) + (c.y < split_y_abs ? 0 : 2);
      ++counts[q];
      scratch_[static_cast<std::size_t>(k - parent.begin)] = key << 2 | q;
    }
    std::int32_t starts[4];
    starts[0] = parent.begin;
    for (int q = 1; q < 4; ++q) starts[q] = starts[q - 1] + counts[q - 1];
    std::int32_t cursor[4] = {starts[0], starts[1], starts[2], starts[3]};
    for (const std::int32_t tagged : scratch_)
      keys[static_cast<std::size_t>(cursor[tagged & 3]++)] = tagged >> 2;

    const int xs[3] = {parent.x0, split_x, parent.x1};
    const int ys[3] = {parent.y0, split_y, parent.y1};
    int made = 0;
    for (int q = 0; q < 4; ++q) {
      if (counts[q] == 0) continue;
      const int qx = q & 1, qy = q >> 1;
      add({xs[qx], ys[qy], xs[qx + 1], ys[qy + 1], starts[q], starts[q] + counts[q], true});
      children[made++] = static_cast<std::int32_t>(nodes.size()) - 1;
    }
    return made;
  }

 private:
  const std::vector<Candidate>& candidates_;
  int min_x_, min_y_;
  std::vector<std::int32_t>& scratch_;
};

}  // namespace

void distribute_quadtree(const std::vector<Candidate>& candidates, int min_x, int max_x, int min_y,
                         int max_y, int n_wanted, std::vector<std::int32_t>& selected,
                         DistributionScratch& scratch) {
  if (candidates.empty() || n_wanted <= 0) return;
  const int width = max_x - min_x, height = max_y - min_y;
  assert(width > 0 && height > 0);
  assert(candidates.size() < (std::size_t{1} << 29));  // Quadtree::divide tags keys with 2 bits

  Quadtree tree(candidates, min_x, min_y, scratch);
  // Initial nodes side by side, about square (ORB-SLAM2); at least one, for portrait images.
  const int initial = std::max(
      1, static_cast<int>(std::lround(static_cast<float>(width) / static_cast<float>(height))));
  const float node_width = static_cast<float>(width) / static_cast<float>(initial);
  std::vector<std::int32_t>& counts = scratch.initial_counts;
  std::vector<std::int32_t>& owner = scratch.owner;
  counts.assign(static_cast<std::size_t>(initial), 0);
  owner.resize(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const float x = static_cast<float>(candidates[i].x - min_x);
    owner[i] = std::min(initial - 1, static_cast<int>(x / node_width));
    ++counts[static_cast<std::size_t>(owner[i])];
  }
  tree.keys.resize(candidates.size());
  {
    // Counting sort of the keys by initial node; counts become each node's write cursor.
    std::int32_t start = 0;
    for (int i = 0; i < initial; ++i) {
      const int x0 = static_cast<int>(node_width * static_cast<float>(i));
      const int x1 = static_cast<int>(node_width * static_cast<float>(i + 1));
      if (counts[static_cast<std::size_t>(i)] > 0)
        tree.add({x0, 0, x1, height, start, start + counts[static_cast<std::size_t>(i)], true});
      const std::int32_t count = counts[static_cast<std::size_t>(i)];
      counts[static_cast<std::size_t>(i)] = start;
      start += count;
    }
    for (std::size_t i = 0; i < candidates.size(); ++i)
      tree.keys[static_cast<std::size_t>(counts[static_cast<std::size_t>(owner[i])]++)] =
          static_cast<std::int32_t>(i);
  }

  // Expansion order for the final, careful rounds: more candidates first, then top-left first.
  const auto expand_first = [&](std::int32_t a, std::int32_t b) {
    const Node& na = tree.nodes[static_cast<std::size_t>(a)];
    const Node& nb = tree.nodes[static_cast<std::size_t>(b)];
    if (na.size() != nb.size()) return na.size() > nb.size();
    if (na.y0 != nb.y0) return na.y0 < nb.y0;
    return na.x0 < nb.x0;
  };

  std::vector<std::int32_t>& expandable = scratch.expandable;
  std::vector<std::int32_t>& previous = scratch.previous;
  std::int32_t children[4];
  bool finished = false;
  while (!finished) {
    expandable.clear();
    // One full round: every leaf with more than one candidate splits.
    const std::int32_t existing = static_cast<std::int32_t>(tree.nodes.size());
    for (std::int32_t i = 0; i < existing; ++i) {
      const Node& node = tree.nodes[static_cast<std::size_t>(i)];
      if (!node.alive || node.size() <= 1) continue;
      const int made = tree.divide(i, children);
      for (int c = 0; c < made; ++c)
        if (tree.nodes[static_cast<std::size_t>(children[c])].size() > 1)
          expandable.push_back(children[c]);
    }
    // ORB-SLAM2 also stops when a round adds no node, which can leave two candidates sharing a
    // node and the level short of min(n_wanted, candidates); positions are distinct, so
    // splitting on always separates them.
    if (tree.alive_count >= n_wanted || expandable.empty()) {
      finished = true;
    } else if (tree.alive_count + static_cast<int>(expandable.size()) * 3 > n_wanted) {
      // Close to the target: split the fullest nodes one at a time until there are enough.
      while (!finished) {
        previous.swap(expandable);
        expandable.clear();
        std::sort(previous.begin(), previous.end(), expand_first);
        for (std::int32_t index : previous) {
          const int made = tree.divide(index, children);
          for (int c = 0; c < made; ++c)
            if (tree.nodes[static_cast<std::size_t>(children[c])].size() > 1)
              expandable.push_back(children[c]);
          if (tree.alive_count >= n_wanted) break;
        }
        if (tree.alive_count >= n_wanted || expandable.empty()) finished = true;
      }
    }
  }

  // The strongest candidate of each leaf; ORB-SLAM2 may overshoot by up to 3, drop the weakest.
  keep_strongest_of_leaves(tree.nodes, tree.keys, candidates, n_wanted, selected);
}

}  // namespace aief

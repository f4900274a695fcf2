#pragma once
// How many keypoints each block (or quadtree node) of a level keeps (docs/design.md §6).
// Both functions select among the candidates of one level and append the indices (into
// `candidates`) of the chosen ones to `selected`, in no particular order.
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"

namespace aief {

// Candidates of one kept block: candidates[begin, end).
struct BlockRange {
  std::int32_t begin = 0;
  std::int32_t end = 0;
  std::int32_t size() const { return end - begin; }
};

// A quadtree node: rectangle [x0, x1) x [y0, y1) relative to the tree's origin, holding the
// candidates keys[begin, end) of its tree.
struct QuadtreeNode {
  int x0, y0, x1, y1;
  std::int32_t begin, end;
  bool alive;
  std::int32_t size() const { return end - begin; }
};

// Buffers the distributions reuse between calls, so a frame allocates nothing once warm.
struct DistributionScratch {
  std::vector<std::int32_t> order;
  std::vector<std::int32_t> next_in_line;
  std::vector<std::int32_t> keys;
  std::vector<std::int32_t> partition;
  std::vector<std::int32_t> owner;
  std::vector<std::int32_t> initial_counts;
  std::vector<std::int32_t> expandable;
  std::vector<std::int32_t> previous;
  std::vector<QuadtreeNode> nodes;
};

// AIEF's proportional distribution (Eq. 12-17). Block i keeps c_i = min(R_i, k) of its R_i
// candidates, the strongest ones, for the water level k with sum_i min(R_i, k) <= n_wanted as
// large as possible; the remainder goes to the strongest (k+1)-th candidates of the blocks that
// have more than k. The level keeps exactly min(n_wanted, sum_i R_i) and no block exceeds k + 1.
void distribute_proportional(const std::vector<Candidate>& candidates,
                             const std::vector<BlockRange>& blocks, int n_wanted,
                             std::vector<std::int32_t>& selected, DistributionScratch& scratch);

// ORB-SLAM2's DistributeOctTree over candidates in the rectangle [min_x, max_x) x [min_y, max_y)
// of the level: split nodes into four until there are >= n_wanted nodes or none can split, keep
// the strongest candidate of each node. Every ordering has a full tie-break (nodes: more
// candidates first, then top-left first; candidates: stronger()), so repeated calls agree.
// Two departures from ORB-SLAM2, both so the level keeps exactly min(n_wanted, candidates):
// ORB-SLAM2 can end with up to 3 nodes more than wanted (the weakest are dropped here), and it
// stops when a round adds no node (here splitting goes on while a node holds two candidates).
void distribute_quadtree(const std::vector<Candidate>& candidates, int min_x, int max_x, int min_y,
                         int max_y, int n_wanted, std::vector<std::int32_t>& selected,
                         DistributionScratch& scratch);

}  // namespace aief

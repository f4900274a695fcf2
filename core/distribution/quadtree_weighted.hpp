#pragma once
// The quadtree with its splits weighted by block entropy (QuadtreeWeight::entropy,
// docs/design.md §6, "entropy-weighted quadtree"): an entropy-guided variant. The nodes start as
// distribute_quadtree's (side by side, about square); then, instead of splitting every node each
// round, the node of the largest weight splits next, one at a time, until the level has n_wanted
// nodes or no node holds two candidates. A node's weight is the sum over its candidates of their
// block's entropy in 1/256 bit (an integer: the same order under every kernel set and thread
// count), so textured regions are divided finer and keep more keypoints, low-entropy ones fewer.
// Every leaf keeps its strongest candidate (stronger()), so no region with a candidate is left
// without one, except that a last split may overshoot by up to 3 leaves, whose weakest are
// dropped so the level keeps exactly min(n_wanted, candidates), as distribute_quadtree does.
// Ties between weights: more candidates, then top-left first.
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"

namespace aief {

// The weight of a candidate from its block's entropy in bits: round(bits * 256), >= 0.
std::int64_t entropy_weight(double entropy_bits);

// Candidates in [min_x, max_x) x [min_y, max_y) of the level, weights[i] the weight of
// candidates[i] (entropy_weight of its block). Appends the chosen indices to `selected`.
void distribute_quadtree_weighted(const std::vector<Candidate>& candidates,
                                  const std::vector<std::int64_t>& weights, int min_x, int max_x,
                                  int min_y, int max_y, int n_wanted,
                                  std::vector<std::int32_t>& selected);

}  // namespace aief

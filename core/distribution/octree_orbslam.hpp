#pragma once
// ORB-SLAM2/3's DistributeOctTree, step for step (the faithful mode's distribution,
// docs/design.md §6, "ORB-SLAM's own tie-breaks"). distribute_quadtree
// (core/distribution/distribution.hpp) gives every ordering a full tie-break and keeps exactly N;
// this one keeps what ORB-SLAM keeps where ORB-SLAM is deterministic, which is everywhere given the
// candidates' order:
//   - nodes live in a list; a divided node's non-empty children go to the list's front in the
//     order UL, UR, BL, BR (so they sit reversed), and the node is erased;
//   - the careful rounds sort (size, node) pairs with ORB-SLAM3's compareNodes (size, then the
//     left edge; equal pairs stay where std::sort puts them, which depends only on the sequence,
//     rebuilt here in the same order) and divide from the back, stopping as soon as the list
//     holds N nodes, so the level may keep up to 3 more than N, as ORB-SLAM does;
//   - a node keeps its first candidate of the highest score, in the candidates' order
//     (core/detection/orbslam_cells.hpp gives ORB-SLAM's).
// The selection is appended to `selected` in the list's order.
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"

namespace aief {

// Candidates in [min_x, max_x) x [min_y, max_y) of the level (ORB-SLAM's minBorderX, maxBorderX,
// ...), n_wanted the level's N.
void distribute_octree_orbslam(const std::vector<Candidate>& candidates, int min_x, int max_x,
                               int min_y, int max_y, int n_wanted,
                               std::vector<std::int32_t>& selected);

}  // namespace aief

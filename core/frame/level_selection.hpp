#pragma once
// Stage 4, first half, on one level: which of the candidates in the blocks a mask keeps a budget
// chooses, by the options' distribution: proportional over the kept blocks (through the
// candidate pool, core/distribution/candidate_pool.hpp, when there are more candidates than the
// pool holds), or ORB-SLAM2's quadtree over all kept candidates as one set.
#include <cstdint>
#include <vector>

#include "aief/options.hpp"
#include "core/distribution/candidate_pool.hpp"
#include "core/distribution/distribution.hpp"
#include "core/entropy/block_mask.hpp"
#include "core/level/level_blocks.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

// Selection's own buffers for one level.
struct SelectionScratch {
  std::vector<BlockRange> kept_blocks;     // proportional: the kept blocks' candidate ranges
  std::vector<Candidate> pooled;           // proportional, pooled: the pool's candidates
  std::vector<std::int32_t> pooled_index;  // ... each one's index in the level's candidates
  std::vector<BlockRange> pooled_blocks;   // ... and the kept blocks' ranges in the pool
  CandidatePoolScratch pool;
  std::vector<Candidate> quadtree_set;         // quadtree: the kept blocks' candidates
  std::vector<std::int32_t> quadtree_index;    // ... each one's index in the level's candidates
  std::vector<std::int64_t> quadtree_weights;  // QuadtreeWeight::entropy: each one's weight
  DistributionScratch distribution;
};

// Indices into blocks.candidates of at most `budget` candidates of the kept blocks, in no
// particular order. budget > 0 and the level usable.
void select_candidates(const PyramidLevel& level, const LevelBlocks& blocks, BlockMask mask,
                       const ExtractorOptions& options, int budget, SelectionScratch& scratch,
                       std::vector<std::int32_t>& selected);

}  // namespace aief

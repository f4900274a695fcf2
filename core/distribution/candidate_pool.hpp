#pragma once
// The per-level candidate pool (docs/design.md §6): before the water-level
// distribution, a level keeps only its strongest P x N_n candidates over the kept blocks. Without
// it a level with about one candidate per block fills its budget with the weak corners of the
// fast_min_threshold retry, which match less often (Oxford: 54-68% correct below score 20, 82%
// from 60). The distribution itself is unchanged; it runs on the pooled candidates.
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"
#include "core/distribution/distribution.hpp"

namespace aief {

// Candidates a level keeps in its pool: ceil(P * N_n), never fewer than N_n; -1 when there is no
// pool (P infinite or N_n huge), so every candidate goes to the distribution.
std::int64_t candidate_pool_size(double pool_factor, int n_wanted);

// Buffers the pool reuses between calls.
struct CandidatePoolScratch {
  std::vector<std::int32_t> tied;         // indices of the candidates at the cut-off strength
  std::vector<BlockRange> spans;          // the blocks' ranges, merged where they touch
  std::vector<std::int32_t> kept_before;  // per candidate: how many the pool took before it
  std::vector<std::int32_t> kept_after;   // ... and with it
};

// The `pool_size` strongest candidates of `blocks` (stronger(): strength, score, y, x), copied
// block by block into `pooled` (each block's candidates keep their order) with their indices into
// `candidates` in `pooled_index` and the pooled ranges in `pooled_blocks` (blocks left empty are
// dropped). Requires pool_size >= 0; when the blocks hold no more than pool_size candidates they
// are all copied.
void pool_candidates(const std::vector<Candidate>& candidates,
                     const std::vector<BlockRange>& blocks, std::int64_t pool_size,
                     std::vector<Candidate>& pooled, std::vector<std::int32_t>& pooled_index,
                     std::vector<BlockRange>& pooled_blocks, CandidatePoolScratch& scratch);

}  // namespace aief

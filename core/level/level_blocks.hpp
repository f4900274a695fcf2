#pragma once
// What stages 2 and 3 learn about one level's blocks: each block's entropy, whether it is
// uniform, whether it was detected and which candidates it holds (Eq. 9, the mask a threshold F
// makes of them, is core/entropy/block_mask.hpp).
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"
#include "core/distribution/distribution.hpp"

namespace aief {

struct LevelBlocks {
  std::vector<double> entropy_bits;         // per block, row-major (empty: entropy off)
  std::vector<std::uint8_t> uniform;        // per block: 1 when all its pixels are one gray level
  std::vector<std::uint8_t> detected;       // per block: 1 once its candidates are found
  std::vector<BlockRange> candidate_range;  // per block: its candidates in `candidates`
  std::vector<Candidate>
      candidates;  // the level's detected candidates, block by block, raster order within
  // With a detection mask, per block: 1 when any of its pixels is allowed (made by detection on
  // first need; core/level/caller_mask.hpp). Empty otherwise.
  std::vector<std::uint8_t> allowed;
  // DetectionCells::orbslam: the candidates in ORB-SLAM's order (core/detection/orbslam_cells.hpp),
  // which its octree's tie-breaks read; `candidates` holds them grouped by block. Empty otherwise.
  std::vector<std::int32_t> orbslam_order;

  // A new frame: `blocks` blocks, none detected.
  void reset(int blocks) {
    entropy_bits.clear();
    uniform.clear();
    detected.assign(static_cast<std::size_t>(blocks), 0);
    candidate_range.assign(static_cast<std::size_t>(blocks), BlockRange{});
    candidates.clear();
    allowed.clear();
    orbslam_order.clear();
  }
};

}  // namespace aief

#pragma once
// Stage 3 on one level: the FAST candidates of every block a mask keeps and that is not detected
// yet. Runs of adjacent such blocks in a block row are scored into the score band
// (core/detection/score_band.hpp), with the one-pixel ring suppression reads, then the run's local
// maxima are walked block by block (ORB-SLAM2's retry rule per block). Blocks are detected in
// raster order, so candidates are too.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/detection/orbslam_cells.hpp"
#include "core/distribution/candidate.hpp"
#include "core/entropy/block_mask.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/level/level_blocks.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

// Detection's own buffers for one level.
struct DetectionScratch {
  GrayImage score_band;                     // core/detection/score_band.hpp
  std::vector<std::uint64_t> maxima_bits;   // local maxima of a run of blocks, bit rows
  std::vector<std::uint64_t> allowed_bits;  // the detection mask over one row of such a run
  std::vector<Candidate> run_candidates;    // the candidates of such a run, block by block
  OrbSlamCellScratch cells;  // DetectionCells::orbslam (core/detection/orbslam_cells.hpp)
  std::vector<Candidate> cell_candidates;  // the same, in ORB-SLAM's order
  std::vector<std::int32_t> cell_blocks;   // the block of each
};

// Sizes the scratch for a level of `geometry`.
void size_detection_scratch(const LevelGeometry& geometry, DetectionScratch& scratch);

// Appends the candidates of the blocks `mask` keeps and blocks.detected does not list, and marks
// them detected. With a detection mask on the level, candidates only at its allowed pixels, and
// blocks with none are not scored (core/level/caller_mask.hpp).
void detect_kept_blocks(const PyramidLevel& level, BlockMask mask, const ExtractorOptions& options,
                        const KernelTable& kernels, LevelBlocks& blocks, DetectionScratch& scratch);

}  // namespace aief

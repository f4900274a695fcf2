#pragma once
// Scale selection (ExtractorOptions::scale_selection = extrema, docs/design.md §5 "Scale
// selection"). FAST finds a corner of some size on several adjacent levels; without scale
// selection every level keeps its own copy. With it, once every level has detected every block, a
// candidate stays only where it is a scale extremum: no candidate of level n - 1 or n + 1 within
// kScaleWindow pixels of the coarser of the two levels (on each axis, through the pixel-centre map
// of core/level/keypoint_position.hpp, in exact integers) is stronger. Strength is the ranking's
// (rank_strength: the cross sum or the peak score), with no scale normalisation: FAST's score is
// an intensity difference at a fixed ring radius, the same on every level that resolves the
// corner and lower on the levels that blur it. Ties go to the finer level (its positions are the
// more precise). The levels then select as without it (budgets N_n, threshold fallback, shortfall).
//
// Integer arithmetic on the candidates alone, so the same on every kernel set and thread count;
// linear in the candidates (a bucket grid per level), no pixel is read. Measured worse than
// keeping every level's copies on the hard families and Oxford (docs/evaluation.md, "Scale
// selection"), so off in every mode: a binary descriptor of a fixed patch per level matches a
// corner across blur and zoom through the copies on neighbouring levels.
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"
#include "core/level/level_blocks.hpp"

namespace aief {

// The window's half side, in pixels of the coarser of two adjacent levels: FAST's own
// suppression is 3 x 3, so a corner found on two levels lands within one coarse pixel of itself.
inline constexpr int kScaleWindow = 1;

// A level's candidates in buckets of kScaleBucket x kScaleBucket level pixels (counting sort).
struct ScaleIndex {
  int width = 0, height = 0;         // the level's size
  int cols = 0, rows = 0;            // buckets
  std::vector<std::int32_t> starts;  // cols * rows + 1
  std::vector<std::int32_t> order;   // candidate indices, bucket by bucket
};
inline constexpr int kScaleBucket = 8;

// Indexes `candidates` of a width x height level.
void index_candidates(const std::vector<Candidate>& candidates, int width, int height,
                      ScaleIndex& index);

// One level as scale selection reads it.
struct ScaleLevel {
  const std::vector<Candidate>* candidates = nullptr;  // null: no such level or not usable
  const ScaleIndex* index = nullptr;
};

// keep[i] = 1 when candidate i of `here` (level n) is a scale extremum against `finer` (n - 1)
// and `coarser` (n + 1), either of which may be empty.
void mark_scale_extrema(const ScaleLevel& here, const ScaleLevel& finer, const ScaleLevel& coarser,
                        std::vector<std::uint8_t>& keep);

// Removes the candidates with keep[i] == 0, keeping the order, and the block ranges with them.
void remove_unkept_candidates(const std::vector<std::uint8_t>& keep, LevelBlocks& blocks);

}  // namespace aief

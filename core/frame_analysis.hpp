#pragma once
// Everything about one image that does not depend on the entropy threshold F (DESIGN.md
// sections 1 and 3): pyramid levels, block entropies, FAST candidates per block (detected on
// demand, only for the blocks a threshold keeps, plus the one-pixel ring suppression reads),
// and orientations and descriptors (computed on demand, memoised per candidate). A threshold is
// then a block mask, a distribution and the descriptors of the chosen candidates: select().
//
// The stages are separate functions per level so that parallel/ can schedule them; each writes
// only into its own level, so the result never depends on which thread ran what.
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/candidate.hpp"
#include "core/candidate_pool.hpp"
#include "core/distribution.hpp"
#include "core/kernel_table.hpp"
#include "core/level_geometry.hpp"
#include "core/pyramid_resize.hpp"

namespace aief {

// How many times select() runs on one frame, which decides how the blurred level is held.
enum class Selections {
  one,   // extract: the rows descriptors read are blurred into a small band sliding down the level
  many,  // the sweep: each level blurred whole once and kept, for every threshold's descriptors
};

struct LevelState {
  LevelGeometry geometry;
  ResizePlan resize_plan;  // from the previous level (empty for level 0)
  ImageView pixels;        // the level: the caller's image for level 0, else `image`
  GrayImage image;         // pixels of levels >= 1 (unused for level 0)
  // Blurred rows for rBRIEF: the whole level (Selections::many, made on first describe) or a
  // band of rows [blurred_top, blurred_end) that slides down as points are described.
  GrayImage blurred;
  int blurred_top = 0, blurred_end = 0;
  // FAST scores of one block row and its one-pixel ring: band row i is level row score_top + i.
  GrayImage score_band;

  std::vector<double> block_entropy;       // bits, per block, row-major (empty: entropy off)
  std::vector<std::uint8_t> block_uniform;  // per block: 1 when all its pixels are one gray level
  std::vector<std::uint8_t> block_detected;
  std::vector<BlockRange> block_candidates;  // per block: its candidates, raster order

  std::vector<Candidate> candidates;           // all detected candidates of the level
  // Orientation and descriptor memo: slot of each candidate (-1: not described yet) into dense
  // arrays that hold only the described ones, a few thousand among the 10^5 candidates of a
  // large frame.
  std::vector<std::int32_t> candidate_memo_slot;
  std::vector<float> memo_angle_deg;
  std::vector<Descriptor> memo_descriptor;
  // Selections::many: the candidates in raster order and each one's place in it (built by the
  // first select after detection), so that every threshold's selection is put in raster order by
  // a bit per place instead of a sort.
  std::vector<std::int32_t> raster_order, raster_rank;
  std::vector<std::uint64_t> scratch_rank_bits;

  // Per-level scratch, so levels can run on different threads.
  std::vector<std::int32_t> scratch_xs;
  std::vector<std::uint64_t> scratch_maxima_bits;  // local maxima of a run of blocks, bit rows
  std::vector<std::int32_t> scratch_fresh_blocks;
  std::vector<std::int32_t> scratch_selected;
  std::vector<BlockRange> scratch_blocks;
  std::vector<Candidate> scratch_candidates;
  std::vector<PixelPoint> scratch_points;
  std::vector<PixelPoint> scratch_band_points;
  std::vector<std::uint64_t> scratch_blur_columns;
  std::vector<std::int32_t> scratch_m10, scratch_m01;
  std::vector<float> scratch_angles;
  std::vector<std::uint8_t> scratch_descriptors;
  DistributionScratch scratch_distribution;
  std::vector<Candidate> scratch_pooled;
  std::vector<std::int32_t> scratch_pooled_index;
  std::vector<BlockRange> scratch_pooled_blocks;
  CandidatePoolScratch scratch_pool;

  bool usable() const { return geometry.grid.count() > 0; }
};

class FrameAnalysis {
 public:
  // Checks the image against the options (throws aief::Error) and sizes the levels. Reuses all
  // buffers when the size is the same as the previous frame's. The image is read in place (it
  // is level 0) and must outlive the analysis of this frame.
  void start(ImageView image, const ExtractorOptions& options, const KernelTable& kernels,
             Selections selections = Selections::one);

  int level_count() const { return static_cast<int>(levels_.size()); }
  LevelState& level(int n) { return levels_[static_cast<std::size_t>(n)]; }
  const LevelState& level(int n) const { return levels_[static_cast<std::size_t>(n)]; }

  // Stage 1 per level, in level order: the level's pixels (from the input or level n - 1).
  void build_level_rows(int n, int y_begin, int y_end);
  void build_level(int n) { build_level_rows(n, 0, level(n).geometry.height); }
  // Stage 2: block entropies of level n (no-op with entropy off).
  void compute_entropies(int n);
  // Stage 3: FAST candidates of every block of level n kept at threshold F not yet detected.
  void detect(int n, double threshold);
  // Stage 4: the keypoints of level n at threshold F: distribution, orientation, descriptors.
  // Appends the chosen candidate indices (raster order) to `chosen`.
  void select(int n, double threshold, std::vector<std::int32_t>& chosen);
  // The same with a budget other than N_n (the shortfall rule, core/threshold_fallback.hpp).
  void select(int n, double threshold, int budget, std::vector<std::int32_t>& chosen);

  // Whether block b of level n is kept at threshold F (always, with entropy off).
  bool block_kept(int n, int b, double threshold) const;
  // Candidates in the blocks kept at F, over all levels (after detect at F).
  std::int64_t candidate_count(double threshold) const;
  // The same for level n alone.
  std::int64_t level_candidate_count(int n, double threshold) const;
  int blocks_total() const;
  int blocks_kept(double threshold) const;
  int level_blocks_kept(int n, double threshold) const;
  // Entropy of level 0 (Eq. 7) in the options' measure; 0 with entropy off. After stage 2.
  double image_entropy_bits() const;

  // Writes the keypoints and descriptors of the chosen candidates of every level.
  void assemble(const std::vector<std::vector<std::int32_t>>& chosen, Features& out) const;

  const ExtractorOptions& options() const { return options_; }

 private:
  void compute_score_rows(LevelState& level, int score_top, int y_begin, int y_end, int x_begin, int x_end);
  void detect_run(LevelState& level, int r, int c_begin, int c_end, int score_top);
  void describe(LevelState& level, const std::vector<std::int32_t>& indices);
  static void sort_by_raster_rank(LevelState& level, std::vector<std::int32_t>& indices);
  void describe_through_band(LevelState& level, int count);

  ExtractorOptions options_;
  Selections selections_ = Selections::one;
  const KernelTable* kernels_ = nullptr;
  int width_ = 0, height_ = 0;
  std::vector<LevelState> levels_;
  double image_entropy_bits_ = 0;
};

}  // namespace aief

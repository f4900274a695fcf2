#pragma once
// Everything about one image that does not depend on the entropy threshold F (docs/design.md):
// pyramid levels, block entropies, FAST candidates per block (detected on demand, only for the
// blocks a threshold keeps, plus the one-pixel ring suppression reads), and orientations and
// descriptors (computed on demand, memoised per candidate). A threshold is then a block mask, a
// distribution and the descriptors of the chosen candidates: select().
//
// The stages are separate functions per level so that the frame pipeline
// (core/frame/frame_pipeline.hpp) can schedule them; each writes only into its own level, so the
// result never depends on which thread ran what. Each stage's work is in a file of its own:
// core/entropy/level_entropy.hpp, core/detection/level_detection.hpp (with
// core/detection/score_band.hpp), core/frame/level_selection.hpp,
// core/distribution/raster_order.hpp, core/description/level_description.hpp.
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/description/level_description.hpp"
#include "core/detection/detection_smoothing.hpp"
#include "core/detection/level_detection.hpp"
#include "core/detection/scale_selection.hpp"
#include "core/distribution/raster_order.hpp"
#include "core/entropy/block_mask.hpp"
#include "core/entropy/low_entropy_sharpen.hpp"
#include "core/frame/level_selection.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/level/level_blocks.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

class FrameAnalysis {
 public:
  // Checks the image against the options (throws aief::Error) and sizes the levels. Reuses all
  // buffers when the size is the same as the previous frame's. The image is read in place (it
  // is level 0) and must outlive the analysis of this frame. detection_mask (empty: none) is the
  // image's size (else aief::Error), non-zero where keypoints may be: each level's is made with
  // its pixels and detection takes candidates only where it allows (core/level/caller_mask.hpp).
  void start(ImageView image, const ExtractorOptions& options, const KernelTable& kernels,
             Selections selections = Selections::one, ImageView detection_mask = {});

  int level_count() const { return static_cast<int>(levels_.size()); }
  // Level n's pixels (after stage 1) and what stages 2 and 3 found in its blocks.
  const PyramidLevel& level(int n) const { return at(n).pyramid; }
  const LevelBlocks& blocks(int n) const { return at(n).blocks; }

  // Stage 1 per level, in level order: the level's pixels (from the input or level n - 1), and
  // its detection mask when there is one.
  void build_level_rows(int n, int y_begin, int y_end);
  void build_level(int n) { build_level_rows(n, 0, level(n).geometry.height); }
  // Stage 2: block entropies of level n (no-op with entropy off and no option reading them),
  // then with low_entropy_sharpen the sharpened pixels detection reads, then with
  // detection_smoothing those smoothed.
  void compute_entropies(int n);
  // Stage 3: FAST candidates of every block of level n kept at threshold F not yet detected.
  void detect(int n, double threshold);
  // Scale selection (core/detection/scale_selection.hpp), after every level detected every
  // block, in three passes over the levels (each pass may run its levels in parallel): index
  // level n's candidates, mark its scale extrema (reads levels n - 1 and n + 1), remove the rest.
  void index_scales(int n);
  void mark_scale_extrema(int n);
  void keep_scale_extrema(int n);
  // Stage 4: the keypoints of level n at threshold F: distribution, orientation, descriptors.
  // Writes the chosen candidate indices (raster order) to `chosen`.
  void select(int n, double threshold, std::vector<std::int32_t>& chosen);
  // The same with a budget other than N_n (the shortfall, core/entropy/threshold_fallback.hpp).
  void select(int n, double threshold, int budget, std::vector<std::int32_t>& chosen);
  // select() in its two parts, for a caller that spreads the work (core/sweep/spread_sweep.hpp):
  // choose() distributes and orders (no descriptions), describe() describes the candidates
  // `indices` of level n not described yet (any subset, in any pieces: the same descriptors).
  void choose(int n, double threshold, int budget, std::vector<std::int32_t>& chosen);
  void describe(int n, const std::vector<std::int32_t>& indices);
  // Selections::many: what level n's descriptor reads over the whole level, the blurred level or
  // the integral image (describe() makes it when missing).
  bool descriptor_input_ready(int n) const { return at(n).descriptions.descriptor_input_ready(); }
  void prepare_descriptor_input(int n) {
    at(n).descriptions.prepare_descriptor_input(at(n).pyramid, *kernels_);
  }
  bool described(int n, std::int32_t i) const { return at(n).descriptions.described(i); }

  // Eq. 9 on level n at F (every block kept with entropy off).
  BlockMask mask(int n, double threshold) const;
  // Whether block b of level n is kept at threshold F.
  bool block_kept(int n, int b, double threshold) const { return mask(n, threshold).kept(b); }
  // Candidates in the blocks of level n kept at F (after detect at F).
  std::int64_t level_candidate_count(int n, double threshold) const;
  int blocks_total() const;
  int blocks_kept(double threshold) const;
  int level_blocks_kept(int n, double threshold) const;
  // Entropy of level 0 (Eq. 7) in the options' measure; 0 with entropy off. After stage 2.
  double image_entropy_bits() const { return image_entropy_bits_; }

  // Stage 5: the keypoints and descriptors of the chosen candidates of every level.
  void assemble(const std::vector<std::vector<std::int32_t>>& chosen, Features& out) const;

  const ExtractorOptions& options() const { return options_; }

 private:
  // One level, its state split by job; each stage gets only the parts it reads and writes.
  struct Level {
    PyramidLevel pyramid;
    LevelBlocks blocks;
    LevelDescriptions descriptions;
    RasterRanks raster_ranks;  // Selections::many
    DetectionScratch detection;
    SharpenScratch sharpen;      // ExtractorOptions::low_entropy_sharpen
    SmoothingScratch smoothing;  // ExtractorOptions::detection_smoothing
    SelectionScratch selection;
    ScaleIndex scale_index;                // ExtractorOptions::scale_selection
    std::vector<std::uint8_t> scale_keep;  // the same
    std::vector<std::int32_t> selected;
  };
  void entropies_and_sharpening(int n);  // stage 2 up to the sharpening
  const Level& at(int n) const { return levels_[static_cast<std::size_t>(n)]; }
  Level& at(int n) { return levels_[static_cast<std::size_t>(n)]; }

  ExtractorOptions options_;
  Selections selections_ = Selections::one;
  ImageView detection_mask_;  // the caller's (empty: none)
  const KernelTable* kernels_ = nullptr;
  int width_ = 0, height_ = 0;
  std::vector<Level> levels_;
  double image_entropy_bits_ = 0;
};

}  // namespace aief

#include "core/frame/frame_analysis.hpp"

#include <cstdint>
#include <string>

#include "aief/error.hpp"
#include "core/entropy/level_entropy.hpp"
#include "core/frame/image_checks.hpp"
#include "core/level/caller_mask.hpp"
#include "core/level/keypoint_position.hpp"

namespace aief {

void FrameAnalysis::start(ImageView image, const ExtractorOptions& options,
                          const KernelTable& kernels, Selections selections,
                          ImageView detection_mask) {
  check_image(image, options);
  if (!detection_mask.empty() &&
      (detection_mask.width != image.width || detection_mask.height != image.height))
    throw Error("mask " + std::to_string(detection_mask.width) + "x" +
                std::to_string(detection_mask.height) + " is not the image's size " +
                std::to_string(image.width) + "x" + std::to_string(image.height));
  if (!detection_mask.empty() && options.detection_cells == DetectionCells::orbslam)
    throw Error("a detection mask needs detection_cells blocks (ORB-SLAM's cells take no mask)");
  detection_mask_ = detection_mask;
  const bool same_geometry =
      image.width == width_ && image.height == height_ && options.n_levels == options_.n_levels &&
      options.scale_factor == options_.scale_factor && options.block_size == options_.block_size &&
      options.n_features == options_.n_features &&
      options.pyramid_resampling == options_.pyramid_resampling && !levels_.empty();
  options_ = options;
  selections_ = selections;
  kernels_ = &kernels;
  width_ = image.width;
  height_ = image.height;
  image_entropy_bits_ = 0;

  if (!same_geometry) {
    std::vector<LevelGeometry> geometry = level_geometry(width_, height_, options_);
    levels_.resize(geometry.size());
    for (std::size_t n = 0; n < geometry.size(); ++n) {
      PyramidLevel& pyramid = levels_[n].pyramid;
      pyramid.geometry = std::move(geometry[n]);
      if (!pyramid.usable()) continue;
      if (n > 0) {
        pyramid.image.resize(pyramid.geometry.width, pyramid.geometry.height);
        const LevelGeometry& above = levels_[n - 1].pyramid.geometry;
        pyramid.resize_plan = make_resize_plan(above.width, above.height, pyramid.geometry.width,
                                               pyramid.geometry.height);
        if (options_.pyramid_resampling == PyramidResampling::opencv)
          pyramid.opencv_plan = make_opencv_resize_plan(
              above.width, above.height, pyramid.geometry.width, pyramid.geometry.height);
      }
      size_detection_scratch(pyramid.geometry, levels_[n].detection);
    }
  }
  for (std::size_t n = 0; n < levels_.size(); ++n) {
    Level& level = levels_[n];
    level.pyramid.pixels = n == 0 ? image : level.pyramid.image.view();
    level.pyramid.detection_pixels = level.pyramid.pixels;
    if (detection_mask_.empty())
      level.pyramid.detection_mask.resize(0, 0);
    else if (level.pyramid.usable())
      level.pyramid.detection_mask.resize(level.pyramid.geometry.width,
                                          level.pyramid.geometry.height);
    level.descriptions.set_descriptor(options_.descriptor);  // before start: what it sizes
    level.descriptions.start(level.pyramid.geometry, selections_);
    level.descriptions.set_orientation(options_.orientation);
    level.blocks.reset(level.pyramid.geometry.grid.count());
    level.raster_ranks.clear();
  }
}

void FrameAnalysis::build_level_rows(int n, int y_begin, int y_end) {
  PyramidLevel& pyramid = at(n).pyramid;
  if (!pyramid.usable()) return;
  if (n > 0 && options_.pyramid_resampling == PyramidResampling::opencv)
    kernels_->resize_opencv_linear_rows(level(n - 1).pixels, pyramid.opencv_plan,
                                        pyramid.image.mutable_view(), y_begin, y_end);
  else if (n > 0)  // level 0 is the input itself
    kernels_->resize_bilinear_rows(level(n - 1).pixels, pyramid.resize_plan,
                                   pyramid.image.mutable_view(), y_begin, y_end);
  if (detection_mask_.empty()) return;
  if (n == 0) {
    binarise_mask_rows(detection_mask_, pyramid.detection_mask.mutable_view(), y_begin, y_end);
  } else {
    kernels_->resize_bilinear_rows(level(n - 1).detection_mask.view(), pyramid.resize_plan,
                                   pyramid.detection_mask.mutable_view(), y_begin, y_end);
    clear_partial_mask_rows(pyramid.detection_mask.mutable_view(), y_begin, y_end);
  }
}

void FrameAnalysis::compute_entropies(int n) {
  entropies_and_sharpening(n);
  // After the sharpening (which reads the block entropies), before any detection, as it.
  Level& level = at(n);
  const int passes = detection_smoothing_passes(options_.detection_smoothing);
  if (passes > 0 && level.pyramid.usable()) {
    smooth_for_detection(level.pyramid.detection_pixels, passes, *kernels_, level.smoothing,
                         level.pyramid.smoothed);
    level.pyramid.detection_pixels = level.pyramid.smoothed.view();
  }
}

void FrameAnalysis::entropies_and_sharpening(int n) {
  Level& level = at(n);
  const bool mask_on = options_.entropy != EntropyMeasure::off;
  // The entropy-weighted quadtree, the per-block FAST thresholds and the sharpening read the block
  // entropies with the mask off too (histogram); the frame's own entropy stays the mask's (0
  // without it).
  const bool entropies_needed = (options_.distribution == Distribution::quadtree &&
                                 options_.quadtree_weight == QuadtreeWeight::entropy) ||
                                (options_.detection_cells == DetectionCells::blocks &&
                                 options_.fast_threshold_from == FastThresholdFrom::entropy) ||
                                options_.low_entropy_sharpen;
  if ((!mask_on && !entropies_needed) || !level.pyramid.usable()) return;
  std::uint32_t whole[256] = {};
  compute_block_entropies(level.pyramid.pixels, level.pyramid.geometry.grid,
                          mask_on ? options_.entropy : EntropyMeasure::histogram, *kernels_,
                          level.blocks, n == 0 && mask_on ? whole : nullptr);
  if (n == 0 && mask_on)
    image_entropy_bits_ =
        whole_level_entropy_bits(level.pyramid.pixels, options_.entropy, *kernels_, whole);
  // Once per level and frame, before any detection: every threshold F (the fallback, the sweep)
  // then detects on the same pixels, so candidates stay memoised per block.
  if (options_.low_entropy_sharpen &&
      sharpen_low_entropy_blocks(level.pyramid.pixels, level.pyramid.geometry.grid,
                                 level.blocks.entropy_bits, *kernels_, level.sharpen,
                                 level.pyramid.sharpened))
    level.pyramid.detection_pixels = level.pyramid.sharpened.view();
}

BlockMask FrameAnalysis::mask(int n, double threshold) const {
  if (options_.entropy == EntropyMeasure::off) return {};
  return {&at(n).blocks.entropy_bits, threshold};
}

void FrameAnalysis::detect(int n, double threshold) {
  Level& level = at(n);
  if (!level.pyramid.usable()) return;
  detect_kept_blocks(level.pyramid, mask(n, threshold), options_, *kernels_, level.blocks,
                     level.detection);
  level.descriptions.track(level.blocks.candidates.size());
}

void FrameAnalysis::index_scales(int n) {
  Level& level = at(n);
  if (!level.pyramid.usable()) return;
  index_candidates(level.blocks.candidates, level.pyramid.geometry.width,
                   level.pyramid.geometry.height, level.scale_index);
}

void FrameAnalysis::mark_scale_extrema(int n) {
  Level& level = at(n);
  if (!level.pyramid.usable()) return;
  const auto view = [&](int m) {
    if (m < 0 || m >= level_count() || !at(m).pyramid.usable()) return ScaleLevel{};
    return ScaleLevel{&at(m).blocks.candidates, &at(m).scale_index};
  };
  aief::mark_scale_extrema(view(n), view(n - 1), view(n + 1), level.scale_keep);
}

void FrameAnalysis::keep_scale_extrema(int n) {
  Level& level = at(n);
  if (!level.pyramid.usable()) return;
  remove_unkept_candidates(level.scale_keep, level.blocks);
  level.descriptions.track(level.blocks.candidates.size());
}

void FrameAnalysis::select(int n, double threshold, std::vector<std::int32_t>& chosen) {
  select(n, threshold, level(n).geometry.n_features, chosen);
}

void FrameAnalysis::select(int n, double threshold, int budget, std::vector<std::int32_t>& chosen) {
  choose(n, threshold, budget, chosen);
  describe(n, chosen);
}

void FrameAnalysis::choose(int n, double threshold, int budget, std::vector<std::int32_t>& chosen) {
  Level& level = at(n);
  chosen.clear();
  if (!level.pyramid.usable() || budget <= 0) return;
  std::vector<std::int32_t>& selected = level.selected;
  select_candidates(level.pyramid, level.blocks, mask(n, threshold), options_, budget,
                    level.selection, selected);
  if (selections_ == Selections::many)
    sort_by_raster_rank(level.blocks.candidates, level.pyramid.geometry.width,
                        level.pyramid.geometry.height, level.raster_ranks, selected);
  else
    sort_in_raster_order(level.blocks.candidates, level.pyramid.geometry.width, selected,
                         level.raster_ranks);
  chosen.assign(selected.begin(), selected.end());
}

void FrameAnalysis::describe(int n, const std::vector<std::int32_t>& indices) {
  Level& level = at(n);
  if (indices.empty()) return;
  level.descriptions.describe(level.pyramid, level.blocks.candidates, indices, *kernels_);
}

std::int64_t FrameAnalysis::level_candidate_count(int n, double threshold) const {
  const LevelBlocks& blocks = this->blocks(n);
  const BlockMask kept = mask(n, threshold);
  std::int64_t total = 0;
  for (int b = 0; b < level(n).geometry.grid.count(); ++b)
    if (kept.kept(b)) total += blocks.candidate_range[static_cast<std::size_t>(b)].size();
  return total;
}

int FrameAnalysis::level_blocks_kept(int n, double threshold) const {
  const BlockMask kept = mask(n, threshold);
  int count = 0;
  for (int b = 0; b < level(n).geometry.grid.count(); ++b) count += kept.kept(b) ? 1 : 0;
  return count;
}

int FrameAnalysis::blocks_total() const {
  int total = 0;
  for (const Level& level : levels_) total += level.pyramid.geometry.grid.count();
  return total;
}

int FrameAnalysis::blocks_kept(double threshold) const {
  int kept = 0;
  for (int n = 0; n < level_count(); ++n) kept += level_blocks_kept(n, threshold);
  return kept;
}

void FrameAnalysis::assemble(const std::vector<std::vector<std::int32_t>>& chosen,
                             Features& out) const {
  out.image_width = width_;
  out.image_height = height_;
  out.descriptor = options_.descriptor;
  out.keypoints.clear();
  out.descriptors.clear();
  for (int n = 0; n < level_count(); ++n) {
    const Level& level = at(n);
    const float scale = level.pyramid.geometry.scale;
    const LevelToImage mapping =
        level_to_image(options_.coordinates, options_.subpixel, scale, width_, height_,
                       level.pyramid.geometry.width, level.pyramid.geometry.height);
    for (std::int32_t i : chosen[static_cast<std::size_t>(n)]) {
      const Candidate& c = level.blocks.candidates[static_cast<std::size_t>(i)];
      Keypoint kp;
      const ImagePoint position = keypoint_position(c, mapping);
      kp.x = position.x;
      kp.y = position.y;
      kp.size = static_cast<float>(kPatchSize) * scale;
      kp.angle_deg = level.descriptions.angle_deg(i);
      kp.response = static_cast<float>(c.score);
      kp.octave = n;
      out.keypoints.push_back(kp);
      out.descriptors.push_back(level.descriptions.descriptor(i));
    }
  }
}

}  // namespace aief

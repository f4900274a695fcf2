#include "core/frame_analysis.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>

#include "aief/error.hpp"
#include "core/block_entropy.hpp"

namespace aief {

namespace {

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void check_image(ImageView image, const ExtractorOptions& options) {
  if (image.width <= 0 || image.height <= 0)
    throw Error("image " + size_text(image.width, image.height) + " is empty");
  if (image.data == nullptr) throw Error("image " + size_text(image.width, image.height) + " has no pixel data");
  if (image.stride < image.width)
    throw Error("image stride " + std::to_string(image.stride) + " is smaller than its width " +
                std::to_string(image.width));
  const long long pixels = static_cast<long long>(image.width) * image.height;
  if (pixels > options.max_image_pixels)
    throw Error("image " + size_text(image.width, image.height) + " has " + std::to_string(pixels) +
                " pixels, more than max_image_pixels = " + std::to_string(options.max_image_pixels));
  if (!level_is_usable(image.width, image.height))
    throw Error("image " + size_text(image.width, image.height) + " is smaller than the " +
                std::to_string(kEdgeBorder) + "-pixel border (needs at least " +
                std::to_string(2 * kEdgeBorder + 1) + " pixels on each side)");
}

}  // namespace

void FrameAnalysis::start(ImageView image, const ExtractorOptions& options, const KernelTable& kernels) {
  check_image(image, options);
  const bool same_geometry = image.width == width_ && image.height == height_ &&
                             options.n_levels == options_.n_levels &&
                             options.scale_factor == options_.scale_factor &&
                             options.block_size == options_.block_size &&
                             options.n_features == options_.n_features && !levels_.empty();
  options_ = options;
  kernels_ = &kernels;
  input_ = image;
  width_ = image.width;
  height_ = image.height;
  image_entropy_bits_ = 0;

  if (!same_geometry) {
    std::vector<LevelGeometry> geometry = level_geometry(width_, height_, options_);
    levels_.resize(geometry.size());
    for (std::size_t n = 0; n < geometry.size(); ++n) {
      LevelState& level = levels_[n];
      level.geometry = std::move(geometry[n]);
      if (!level.usable()) continue;
      const int w = level.geometry.width, h = level.geometry.height;
      level.image.resize(w, h);
      level.blurred.resize(w, h);
      level.scores.resize(w, h);
      if (n > 0) {
        const LevelGeometry& above = levels_[n - 1].geometry;
        level.resize_plan = make_resize_plan(above.width, above.height, w, h);
      }
    }
  }
  for (LevelState& level : levels_) {
    const int blocks = level.geometry.grid.count();
    level.blurred_ready = false;
    level.block_entropy.clear();
    level.block_detected.assign(static_cast<std::size_t>(blocks), 0);
    level.block_candidates.assign(static_cast<std::size_t>(blocks), BlockRange{});
    level.candidates.clear();
    level.candidate_memo_slot.clear();
    level.memo_angle_deg.clear();
    level.memo_descriptor.clear();
  }
}

void FrameAnalysis::build_level_rows(int n, int y_begin, int y_end) {
  LevelState& level = this->level(n);
  if (!level.usable()) return;
  if (n == 0) {
    for (int y = y_begin; y < y_end; ++y)
      std::memcpy(level.image.data() + static_cast<std::ptrdiff_t>(y) * width_, input_.row(y),
                  static_cast<std::size_t>(width_));
    return;
  }
  kernels_->resize_bilinear_rows(this->level(n - 1).image.view(), level.resize_plan,
                                 level.image.mutable_view(), y_begin, y_end);
}

void FrameAnalysis::compute_entropies(int n) {
  LevelState& level = this->level(n);
  if (options_.entropy == EntropyMeasure::off || !level.usable()) return;
  const BlockGrid& grid = level.geometry.grid;
  const ImageView pixels = level.image.view();
  level.block_entropy.resize(static_cast<std::size_t>(grid.count()));
  std::uint32_t whole[256] = {};
  std::uint32_t hist[256];
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      const int x0 = grid.col_edges[static_cast<std::size_t>(c)], x1 = grid.col_edges[static_cast<std::size_t>(c) + 1];
      const int y0 = grid.row_edges[static_cast<std::size_t>(r)], y1 = grid.row_edges[static_cast<std::size_t>(r) + 1];
      std::memset(hist, 0, sizeof hist);
      kernels_->accumulate_histogram(pixels.row(y0) + x0, pixels.stride, x1 - x0, y1 - y0, hist);
      level.block_entropy[static_cast<std::size_t>(r * grid.cols() + c)] = entropy_bits(hist, options_.entropy);
      if (n == 0)
        for (int k = 0; k < 256; ++k) whole[k] += hist[k];
    }
  }
  if (n == 0) {
    // Eq. 7 is over the whole level 0: add the border strips the blocks do not cover.
    const int w = pixels.width, h = pixels.height, b = kEdgeBorder;
    kernels_->accumulate_histogram(pixels.row(0), pixels.stride, w, b, whole);
    kernels_->accumulate_histogram(pixels.row(h - b), pixels.stride, w, b, whole);
    kernels_->accumulate_histogram(pixels.row(b), pixels.stride, b, h - 2 * b, whole);
    kernels_->accumulate_histogram(pixels.row(b) + (w - b), pixels.stride, b, h - 2 * b, whole);
    image_entropy_bits_ = entropy_bits(whole, options_.entropy);
  }
}

bool FrameAnalysis::block_kept(int n, int b, double threshold) const {
  const LevelState& level = this->level(n);
  if (options_.entropy == EntropyMeasure::off) return true;
  return level.block_entropy[static_cast<std::size_t>(b)] > threshold;  // Eq. 9
}

void FrameAnalysis::compute_score_rows(LevelState& level, int y_begin, int y_end, int x_begin, int x_end) {
  // Scores exist on [3, size - 3) only; suppression near the keypoint area never reads further.
  const int w = level.geometry.width, h = level.geometry.height;
  y_begin = std::max(y_begin, 3);
  y_end = std::min(y_end, h - 3);
  x_begin = std::max(x_begin, 3);
  x_end = std::min(x_end, w - 3);
  if (x_begin >= x_end) return;
  const ImageView pixels = level.image.view();
  for (int y = y_begin; y < y_end; ++y)
    kernels_->fast9_scores_row(pixels.row(y), pixels.stride, x_begin, x_end,
                               options_.fast_min_threshold,
                               level.scores.data() + static_cast<std::ptrdiff_t>(y) * w);
}

void FrameAnalysis::detect(int n, double threshold) {
  LevelState& level = this->level(n);
  if (!level.usable()) return;
  const BlockGrid& grid = level.geometry.grid;
  const auto needs = [&](int b) {
    return !level.block_detected[static_cast<std::size_t>(b)] && block_kept(n, b, threshold);
  };

  // Scores of each run of adjacent new blocks in a block row, with the one-pixel ring that
  // suppression reads: one call per row of the run instead of a call per ring segment. Pixels
  // a neighbour already scored are scored again to the same value.
  std::vector<std::int32_t>& fresh = level.scratch_fresh_blocks;  // the blocks detected now
  fresh.clear();
  for (int r = 0; r < grid.rows(); ++r) {
    int c = 0;
    while (c < grid.cols()) {
      if (!needs(r * grid.cols() + c)) { ++c; continue; }
      int end = c;
      while (end < grid.cols() && needs(r * grid.cols() + end)) fresh.push_back(r * grid.cols() + end++);
      compute_score_rows(level, grid.row_edges[static_cast<std::size_t>(r)] - 1, grid.row_edges[static_cast<std::size_t>(r) + 1] + 1,
                         grid.col_edges[static_cast<std::size_t>(c)] - 1, grid.col_edges[static_cast<std::size_t>(end)] + 1);
      c = end;
    }
  }
  for (std::int32_t b : fresh) {
    level.block_detected[static_cast<std::size_t>(b)] = 1;
    detect_block(level, b);
  }
}

void FrameAnalysis::detect_block(LevelState& level, int block) {
  const BlockGrid& grid = level.geometry.grid;
  const int r = block / grid.cols(), c = block % grid.cols();
  const int x0 = grid.col_edges[static_cast<std::size_t>(c)], x1 = grid.col_edges[static_cast<std::size_t>(c) + 1];
  const int y0 = grid.row_edges[static_cast<std::size_t>(r)], y1 = grid.row_edges[static_cast<std::size_t>(r) + 1];
  const int w = level.geometry.width;
  const std::uint8_t* scores = level.scores.data();

  // Local maxima of the score map (threshold-free, see core/fast9.hpp), then the ORB-SLAM2
  // retry rule: fast_threshold, or fast_min_threshold when that leaves the block empty.
  const std::size_t first = level.candidates.size();
  bool any_strong = false;
  level.scratch_xs.resize(static_cast<std::size_t>(x1 - x0));
  for (int y = y0; y < y1; ++y) {
    const std::uint8_t* row = scores + static_cast<std::ptrdiff_t>(y) * w;
    const int found = kernels_->fast9_local_maxima_row(row - w, row, row + w, x0, x1, level.scratch_xs.data());
    for (int i = 0; i < found; ++i) {
      const int x = level.scratch_xs[static_cast<std::size_t>(i)];
      const int score = row[x];
      any_strong = any_strong || score >= options_.fast_threshold;
      level.candidates.push_back({x, y, score});
    }
  }
  if (any_strong) {
    const auto weak = [&](const Candidate& candidate) { return candidate.score < options_.fast_threshold; };
    level.candidates.erase(std::remove_if(level.candidates.begin() + static_cast<std::ptrdiff_t>(first),
                                          level.candidates.end(), weak),
                           level.candidates.end());
  }
  level.block_candidates[static_cast<std::size_t>(block)] = {static_cast<std::int32_t>(first),
                                                             static_cast<std::int32_t>(level.candidates.size())};
  const std::size_t count = level.candidates.size();
  level.candidate_memo_slot.resize(count, -1);
}

void FrameAnalysis::select(int n, double threshold, std::vector<std::int32_t>& chosen) {
  LevelState& level = this->level(n);
  chosen.clear();
  if (!level.usable() || level.geometry.n_features <= 0) return;
  const BlockGrid& grid = level.geometry.grid;

  std::vector<std::int32_t>& selected = level.scratch_selected;
  selected.clear();
  if (options_.distribution == Distribution::proportional) {
    std::vector<BlockRange>& blocks = level.scratch_blocks;
    blocks.clear();
    for (int b = 0; b < grid.count(); ++b)
      if (block_kept(n, b, threshold)) blocks.push_back(level.block_candidates[static_cast<std::size_t>(b)]);
    distribute_proportional(level.candidates, blocks, level.geometry.n_features, selected,
                            level.scratch_distribution);
  } else {
    // The quadtree sees the kept blocks' candidates as one set, over ORB-SLAM2's rectangle.
    std::vector<Candidate>& pool = level.scratch_candidates;
    std::vector<std::int32_t>& pool_index = level.scratch_xs;
    pool.clear();
    pool_index.clear();
    for (int b = 0; b < grid.count(); ++b) {
      if (!block_kept(n, b, threshold)) continue;
      const BlockRange range = level.block_candidates[static_cast<std::size_t>(b)];
      for (std::int32_t i = range.begin; i < range.end; ++i) {
        pool.push_back(level.candidates[static_cast<std::size_t>(i)]);
        pool_index.push_back(i);
      }
    }
    constexpr int kQuadtreeMargin = kEdgeBorder - 3;  // ORB-SLAM2's minBorderX
    distribute_quadtree(pool, kQuadtreeMargin, level.geometry.width - kQuadtreeMargin, kQuadtreeMargin,
                        level.geometry.height - kQuadtreeMargin, level.geometry.n_features, selected,
                        level.scratch_distribution);
    for (std::int32_t& index : selected) index = pool_index[static_cast<std::size_t>(index)];
  }
  std::sort(selected.begin(), selected.end(), [&](std::int32_t a, std::int32_t b) {
    return raster_before(level.candidates[static_cast<std::size_t>(a)], level.candidates[static_cast<std::size_t>(b)]);
  });
  describe(level, selected);
  chosen.assign(selected.begin(), selected.end());
}

void FrameAnalysis::describe(LevelState& level, const std::vector<std::int32_t>& indices) {
  std::vector<PixelPoint>& points = level.scratch_points;
  std::vector<std::int32_t>& todo = level.scratch_xs;
  points.clear();
  todo.clear();
  for (std::int32_t i : indices) {
    if (level.candidate_memo_slot[static_cast<std::size_t>(i)] >= 0) continue;
    const Candidate& c = level.candidates[static_cast<std::size_t>(i)];
    points.push_back({c.x, c.y});
    todo.push_back(i);
  }
  if (todo.empty()) return;
  const int count = static_cast<int>(todo.size());
  level.scratch_m10.resize(todo.size());
  level.scratch_m01.resize(todo.size());
  level.scratch_angles.resize(todo.size());
  level.scratch_descriptors.resize(todo.size() * kDescriptorBytes);

  // Orientation on the raw level, descriptors on the blurred one (as ORB-SLAM2).
  kernels_->ic_moments(level.image.view(), points.data(), count, level.scratch_m10.data(), level.scratch_m01.data());
  for (int i = 0; i < count; ++i)
    level.scratch_angles[static_cast<std::size_t>(i)] =
        ic_angle_deg(level.scratch_m10[static_cast<std::size_t>(i)], level.scratch_m01[static_cast<std::size_t>(i)]);
  if (!level.blurred_ready) {
    kernels_->gaussian7_rows(level.image.view(), level.blurred.mutable_view(), 0, level.geometry.height);
    level.blurred_ready = true;
  }
  kernels_->rbrief_describe(level.blurred.view(), points.data(), level.scratch_angles.data(), count,
                            level.scratch_descriptors.data());
  for (int i = 0; i < count; ++i) {
    const std::size_t index = static_cast<std::size_t>(todo[static_cast<std::size_t>(i)]);
    level.candidate_memo_slot[index] = static_cast<std::int32_t>(level.memo_angle_deg.size());
    level.memo_angle_deg.push_back(level.scratch_angles[static_cast<std::size_t>(i)]);
    Descriptor& descriptor = level.memo_descriptor.emplace_back();
    std::memcpy(descriptor.data(), level.scratch_descriptors.data() + static_cast<std::size_t>(i) * kDescriptorBytes,
                kDescriptorBytes);
  }
}

std::int64_t FrameAnalysis::candidate_count(double threshold) const {
  std::int64_t total = 0;
  for (int n = 0; n < level_count(); ++n) {
    const LevelState& level = this->level(n);
    for (int b = 0; b < level.geometry.grid.count(); ++b)
      if (block_kept(n, b, threshold)) total += level.block_candidates[static_cast<std::size_t>(b)].size();
  }
  return total;
}

int FrameAnalysis::blocks_total() const {
  int total = 0;
  for (const LevelState& level : levels_) total += level.geometry.grid.count();
  return total;
}

int FrameAnalysis::blocks_kept(double threshold) const {
  int kept = 0;
  for (int n = 0; n < level_count(); ++n)
    for (int b = 0; b < level(n).geometry.grid.count(); ++b) kept += block_kept(n, b, threshold) ? 1 : 0;
  return kept;
}

double FrameAnalysis::image_entropy_bits() const { return image_entropy_bits_; }

void FrameAnalysis::assemble(const std::vector<std::vector<std::int32_t>>& chosen, Features& out) const {
  out.image_width = width_;
  out.image_height = height_;
  out.keypoints.clear();
  out.descriptors.clear();
  for (int n = 0; n < level_count(); ++n) {
    const LevelState& level = this->level(n);
    const float scale = level.geometry.scale;
    for (std::int32_t i : chosen[static_cast<std::size_t>(n)]) {
      const Candidate& c = level.candidates[static_cast<std::size_t>(i)];
      const std::int32_t slot = level.candidate_memo_slot[static_cast<std::size_t>(i)];
      assert(slot >= 0);
      Keypoint kp;
      kp.x = static_cast<float>(c.x) * scale;
      kp.y = static_cast<float>(c.y) * scale;
      kp.size = static_cast<float>(kPatchSize) * scale;
      kp.angle_deg = level.memo_angle_deg[static_cast<std::size_t>(slot)];
      kp.response = static_cast<float>(c.score);
      kp.octave = n;
      out.keypoints.push_back(kp);
      out.descriptors.push_back(level.memo_descriptor[static_cast<std::size_t>(slot)]);
    }
  }
}

}  // namespace aief

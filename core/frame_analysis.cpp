#include "core/frame_analysis.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstring>
#include <string>

#include "aief/error.hpp"
#include "core/block_entropy.hpp"
#include "core/keypoint_position.hpp"
#include "core/patch_blur.hpp"

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

// Rows of keypoints one band of blurred rows serves at a time; the band adds kEdgeBorder rows
// above and below (every rBRIEF sample lies within kEdgeBorder of its keypoint).
constexpr int kBlurBandKeypointRows = 96;

// Narrowest run of FAST scores computed at once: two AVX-512 batches.
constexpr int kMinScoredRun = 128;

}  // namespace

void FrameAnalysis::start(ImageView image, const ExtractorOptions& options, const KernelTable& kernels,
                          Selections selections) {
  check_image(image, options);
  const bool same_geometry = image.width == width_ && image.height == height_ &&
                             options.n_levels == options_.n_levels &&
                             options.scale_factor == options_.scale_factor &&
                             options.block_size == options_.block_size &&
                             options.n_features == options_.n_features && !levels_.empty();
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
      LevelState& level = levels_[n];
      level.geometry = std::move(geometry[n]);
      if (!level.usable()) continue;
      const int w = level.geometry.width, h = level.geometry.height;
      if (n > 0) {
        level.image.resize(w, h);
        const LevelGeometry& above = levels_[n - 1].geometry;
        level.resize_plan = make_resize_plan(above.width, above.height, w, h);
      }
      int tallest_block_row = 0;
      for (int r = 0; r < level.geometry.grid.rows(); ++r)
        tallest_block_row = std::max(tallest_block_row, level.geometry.grid.row_edges[static_cast<std::size_t>(r) + 1] -
                                                            level.geometry.grid.row_edges[static_cast<std::size_t>(r)]);
      level.score_band.resize(w, tallest_block_row + 2);
    }
  }
  for (std::size_t n = 0; n < levels_.size(); ++n) {
    LevelState& level = levels_[n];
    level.pixels = n == 0 ? image : level.image.view();
    if (level.usable()) {
      const int w = level.geometry.width, h = level.geometry.height;
      if (selections_ == Selections::many) level.blurred.resize(w, h);
      else level.blurred.resize(w, std::min(h, kBlurBandKeypointRows + 2 * kEdgeBorder));
    }
    level.blurred_top = level.blurred_end = 0;
    const int blocks = level.geometry.grid.count();
    level.block_entropy.clear();
    level.block_uniform.clear();
    level.block_detected.assign(static_cast<std::size_t>(blocks), 0);
    level.block_candidates.assign(static_cast<std::size_t>(blocks), BlockRange{});
    level.candidates.clear();
    level.candidate_memo_slot.clear();
    level.raster_rank.clear();
    level.memo_angle_deg.clear();
    level.memo_descriptor.clear();
  }
}

void FrameAnalysis::build_level_rows(int n, int y_begin, int y_end) {
  LevelState& level = this->level(n);
  if (!level.usable() || n == 0) return;  // level 0 is the input itself
  kernels_->resize_bilinear_rows(this->level(n - 1).pixels, level.resize_plan, level.image.mutable_view(),
                                 y_begin, y_end);
}

void FrameAnalysis::compute_entropies(int n) {
  LevelState& level = this->level(n);
  if (options_.entropy == EntropyMeasure::off || !level.usable()) return;
  const BlockGrid& grid = level.geometry.grid;
  const ImageView pixels = level.pixels;
  level.block_entropy.resize(static_cast<std::size_t>(grid.count()));
  level.block_uniform.resize(static_cast<std::size_t>(grid.count()));
  std::uint32_t whole[256] = {};
  std::uint32_t hist[256];
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      const int x0 = grid.col_edges[static_cast<std::size_t>(c)], x1 = grid.col_edges[static_cast<std::size_t>(c) + 1];
      const int y0 = grid.row_edges[static_cast<std::size_t>(r)], y1 = grid.row_edges[static_cast<std::size_t>(r) + 1];
      std::memset(hist, 0, sizeof hist);
      kernels_->accumulate_histogram(pixels.row(y0) + x0, pixels.stride, x1 - x0, y1 - y0, hist);
      const int area = (x1 - x0) * (y1 - y0);
      level.block_entropy[static_cast<std::size_t>(r * grid.cols() + c)] =
          entropy_bits(hist, static_cast<std::uint64_t>(area), options_.entropy);
      level.block_uniform[static_cast<std::size_t>(r * grid.cols() + c)] =
          hist[pixels.row(y0)[x0]] == static_cast<std::uint32_t>(area) ? 1 : 0;
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

void FrameAnalysis::compute_score_rows(LevelState& level, int score_top, int y_begin, int y_end, int x_begin,
                                       int x_end) {
  // Scores exist on [3, size - 3) only; suppression near the keypoint area never reads further.
  const int w = level.geometry.width, h = level.geometry.height;
  y_begin = std::max(y_begin, 3);
  y_end = std::min(y_end, h - 3);
  x_begin = std::max(x_begin, 3);
  x_end = std::min(x_end, w - 3);
  if (x_begin >= x_end) return;
  // A short run is widened within the level (the band is level-wide), so vector kernels see
  // whole batches: a few extra scores cost less than a short row's scalar tail.
  if (x_end - x_begin < kMinScoredRun) {
    x_end = std::min(w - 3, x_begin + kMinScoredRun);
    x_begin = std::max(3, x_end - kMinScoredRun);
  }
  const ImageView pixels = level.pixels;
  for (int y = y_begin; y < y_end; ++y)
    kernels_->fast9_scores_row(pixels.row(y), pixels.stride, x_begin, x_end, options_.fast_min_threshold,
                               level.score_band.mutable_view().row(y - score_top));
}

void FrameAnalysis::detect(int n, double threshold) {
  LevelState& level = this->level(n);
  if (!level.usable()) return;
  const BlockGrid& grid = level.geometry.grid;
  const auto needs = [&](int b) {
    return !level.block_detected[static_cast<std::size_t>(b)] && block_kept(n, b, threshold);
  };

  // Scores of each run of adjacent new blocks in a block row, with the one-pixel ring that
  // suppression reads, go to the level's score band (a block row tall, so it stays in cache):
  // one call per row of the run instead of a call per ring segment, then the run's blocks.
  // Blocks are detected in raster order, so candidates are too.
  for (int r = 0; r < grid.rows(); ++r) {
    const int score_top = grid.row_edges[static_cast<std::size_t>(r)] - 1;
    int c = 0;
    while (c < grid.cols()) {
      if (!needs(r * grid.cols() + c)) { ++c; continue; }
      int end = c;
      while (end < grid.cols() && needs(r * grid.cols() + end)) ++end;
      compute_score_rows(level, score_top, score_top, grid.row_edges[static_cast<std::size_t>(r) + 1] + 1,
                         grid.col_edges[static_cast<std::size_t>(c)] - 1, grid.col_edges[static_cast<std::size_t>(end)] + 1);
      detect_run(level, r, c, end, score_top);
      c = end;
    }
  }
}

void FrameAnalysis::detect_run(LevelState& level, int r, int c_begin, int c_end, int score_top) {
  const BlockGrid& grid = level.geometry.grid;
  const int x_begin = grid.col_edges[static_cast<std::size_t>(c_begin)], x_end = grid.col_edges[static_cast<std::size_t>(c_end)];
  const int y0 = grid.row_edges[static_cast<std::size_t>(r)], y1 = grid.row_edges[static_cast<std::size_t>(r) + 1];
  const MutableImageView scores = level.score_band.mutable_view();

  // Local maxima of the score map (threshold-free, see core/fast9.hpp) over the whole run, one
  // bit row per level row, and the strong ones (score >= fast_threshold) likewise, also OR-ed
  // over the rows, which is what the retry rule asks.
  const int words = fast9_maxima_words(x_end - x_begin);
  std::vector<std::uint64_t>& bits = level.scratch_maxima_bits;
  bits.resize(static_cast<std::size_t>(words) * static_cast<std::size_t>(2 * (y1 - y0) + 1));
  std::uint64_t* strong_any = bits.data();
  std::uint64_t* strong_rows = strong_any + words;
  std::uint64_t* maxima_rows = strong_rows + static_cast<std::ptrdiff_t>(y1 - y0) * words;
  std::fill(strong_any, strong_any + words, std::uint64_t{0});
  for (int y = y0; y < y1; ++y) {
    const std::uint8_t* row = scores.row(y - score_top);
    std::uint64_t* strong_row = strong_rows + static_cast<std::ptrdiff_t>(y - y0) * words;
    kernels_->fast9_local_maxima_bits(row - scores.stride, row, row + scores.stride, x_begin, x_end,
                                      options_.fast_threshold, maxima_rows + static_cast<std::ptrdiff_t>(y - y0) * words,
                                      strong_row);
    for (int k = 0; k < words; ++k) strong_any[k] |= strong_row[k];
  }

  // Each block takes its bit range, in raster order: the strong maxima, or all of them when it
  // has no strong one (ORB-SLAM2's retry rule: fast_threshold, else fast_min_threshold). Reading
  // the strong bit rows skips the weak maxima of a strong block without a compare per maximum.
  for (int c = c_begin; c < c_end; ++c) {
    const int block = r * grid.cols() + c;
    const int begin = grid.col_edges[static_cast<std::size_t>(c)] - x_begin;
    const int end = grid.col_edges[static_cast<std::size_t>(c) + 1] - x_begin;
    const int k_first = begin / 64, k_last = (end - 1) / 64;
    const std::uint64_t first_mask = ~std::uint64_t{0} << (begin % 64);
    const std::uint64_t last_mask = ~std::uint64_t{0} >> (63 - (end - 1) % 64);
    const auto block_bits = [&](const std::uint64_t* words_of_row, int k) {
      std::uint64_t word = words_of_row[k];
      if (k == k_first) word &= first_mask;
      if (k == k_last) word &= last_mask;
      return word;
    };
    bool any_strong = false;
    for (int k = k_first; k <= k_last; ++k) any_strong = any_strong || block_bits(strong_any, k) != 0;
    const std::uint64_t* taken_rows = any_strong ? strong_rows : maxima_rows;
    const bool rank_by_cross = options_.candidate_ranking == CandidateRanking::cross_score;
    const std::size_t first = level.candidates.size();
    const std::ptrdiff_t stride = scores.stride;
    // The cross sum is taken from the scores just read, not reloaded from the stored candidate.
    const auto take = [&](std::uint64_t word, int y, int k) {
      const std::uint8_t* row = scores.row(y - score_top);
      for (; word != 0; word &= word - 1) {
        const int x = x_begin + 64 * k + std::countr_zero(word);
        const std::uint8_t left = row[x - 1], right = row[x + 1], up = row[x - stride], down = row[x + stride];
        level.candidates.push_back(Candidate{x, y, row[x], left, right, up, down, rank_by_cross ? left + right + up + down : 0});
      }
    };
    if (k_first == k_last) {  // the usual block, inside one word: one masked word per row
      const std::uint64_t mask = first_mask & last_mask;
      const std::uint64_t* taken = taken_rows + k_first;
      for (int y = y0; y < y1; ++y, taken += words)
        if (const std::uint64_t word = *taken & mask) take(word, y, k_first);
    } else {
      for (int y = y0; y < y1; ++y)
        for (int k = k_first; k <= k_last; ++k)
          take(block_bits(taken_rows + static_cast<std::ptrdiff_t>(y - y0) * words, k), y, k);
    }
    level.block_detected[static_cast<std::size_t>(block)] = 1;
    level.block_candidates[static_cast<std::size_t>(block)] = {static_cast<std::int32_t>(first),
                                                               static_cast<std::int32_t>(level.candidates.size())};
  }
  level.candidate_memo_slot.resize(level.candidates.size(), -1);
}

void FrameAnalysis::select(int n, double threshold, std::vector<std::int32_t>& chosen) {
  select(n, threshold, level(n).geometry.n_features, chosen);
}

void FrameAnalysis::select(int n, double threshold, int budget, std::vector<std::int32_t>& chosen) {
  LevelState& level = this->level(n);
  chosen.clear();
  if (!level.usable() || budget <= 0) return;
  const BlockGrid& grid = level.geometry.grid;

  std::vector<std::int32_t>& selected = level.scratch_selected;
  selected.clear();
  if (options_.distribution == Distribution::proportional) {
    std::vector<BlockRange>& blocks = level.scratch_blocks;
    blocks.clear();
    std::int64_t total = 0;
    for (int b = 0; b < grid.count(); ++b)
      if (block_kept(n, b, threshold)) {
        blocks.push_back(level.block_candidates[static_cast<std::size_t>(b)]);
        total += blocks.back().size();
      }
    const std::int64_t pool_size = candidate_pool_size(options_.candidate_pool, budget);
    if (pool_size < 0 || total <= pool_size) {
      distribute_proportional(level.candidates, blocks, budget, selected,
                              level.scratch_distribution);
    } else {
      // The level's strongest candidates first (core/candidate_pool.hpp), then the same water level.
      pool_candidates(level.candidates, blocks, pool_size, level.scratch_pooled, level.scratch_pooled_index,
                      level.scratch_pooled_blocks, level.scratch_pool);
      distribute_proportional(level.scratch_pooled, level.scratch_pooled_blocks, budget, selected,
                              level.scratch_distribution);
      for (std::int32_t& index : selected) index = level.scratch_pooled_index[static_cast<std::size_t>(index)];
    }
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
                        level.geometry.height - kQuadtreeMargin, budget, selected,
                        level.scratch_distribution);
    for (std::int32_t& index : selected) index = pool_index[static_cast<std::size_t>(index)];
  }
  if (selections_ == Selections::many) {
    sort_by_raster_rank(level, selected);
  } else {
    std::sort(selected.begin(), selected.end(), [&](std::int32_t a, std::int32_t b) {
      return raster_before(level.candidates[static_cast<std::size_t>(a)], level.candidates[static_cast<std::size_t>(b)]);
    });
  }
  describe(level, selected);
  chosen.assign(selected.begin(), selected.end());
}

namespace {

// Candidate indices in raster order (y, then x; positions are distinct): a counting sort by x,
// then a stable one by y, linear in the candidates and the level's size.
void build_raster_ranks(LevelState& level) {
  const std::vector<Candidate>& candidates = level.candidates;
  const std::size_t count = candidates.size();
  std::vector<std::int32_t>& by_x = level.raster_rank;  // scratch until the end
  std::vector<std::int32_t>& order = level.raster_order;
  by_x.resize(count);
  order.resize(count);
  std::vector<std::int32_t>& starts = level.scratch_xs;
  const auto counting_pass = [&](const std::vector<std::int32_t>* input, std::vector<std::int32_t>& output, int extent,
                                 auto key) {
    starts.assign(static_cast<std::size_t>(extent) + 1, 0);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = input ? static_cast<std::size_t>((*input)[k]) : k;
      ++starts[static_cast<std::size_t>(key(candidates[i])) + 1];
    }
    for (int v = 0; v < extent; ++v) starts[static_cast<std::size_t>(v) + 1] += starts[static_cast<std::size_t>(v)];
    for (std::size_t k = 0; k < count; ++k) {
      const std::int32_t i = input ? (*input)[k] : static_cast<std::int32_t>(k);
      output[static_cast<std::size_t>(starts[static_cast<std::size_t>(key(candidates[static_cast<std::size_t>(i)]))]++)] = i;
    }
  };
  counting_pass(nullptr, by_x, level.geometry.width, [](const Candidate& c) { return c.x; });
  counting_pass(&by_x, order, level.geometry.height, [](const Candidate& c) { return c.y; });
  std::vector<std::int32_t>& rank = level.raster_rank;
  for (std::size_t r = 0; r < count; ++r) rank[static_cast<std::size_t>(order[r])] = static_cast<std::int32_t>(r);
}

}  // namespace

void FrameAnalysis::sort_by_raster_rank(LevelState& level, std::vector<std::int32_t>& indices) {
  if (level.raster_rank.size() != level.candidates.size()) build_raster_ranks(level);
  std::vector<std::uint64_t>& bits = level.scratch_rank_bits;
  bits.assign((level.candidates.size() + 63) / 64, 0);
  for (std::int32_t i : indices) {
    const std::int32_t rank = level.raster_rank[static_cast<std::size_t>(i)];
    bits[static_cast<std::size_t>(rank) / 64] |= std::uint64_t{1} << (rank % 64);
  }
  indices.clear();
  for (std::size_t w = 0; w < bits.size(); ++w)
    for (std::uint64_t word = bits[w]; word != 0; word &= word - 1)
      indices.push_back(level.raster_order[w * 64 + static_cast<std::size_t>(std::countr_zero(word))]);
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
  kernels_->ic_moments(level.pixels, points.data(), count, level.scratch_m10.data(), level.scratch_m01.data());
  for (int i = 0; i < count; ++i)
    level.scratch_angles[static_cast<std::size_t>(i)] =
        ic_angle_deg(level.scratch_m10[static_cast<std::size_t>(i)], level.scratch_m01[static_cast<std::size_t>(i)]);
  if (selections_ == Selections::many) {
    if (level.blurred_end == 0) {
      kernels_->gaussian7_rows(level.pixels, level.blurred.mutable_view(), 0, level.geometry.height, 0,
                               level.geometry.width);
      level.blurred_end = level.geometry.height;
    }
    kernels_->rbrief_describe(level.blurred.view(), points.data(), level.scratch_angles.data(), count,
                              level.scratch_descriptors.data());
  } else {
    describe_through_band(level, count);
  }
  for (int i = 0; i < count; ++i) {
    const std::size_t index = static_cast<std::size_t>(todo[static_cast<std::size_t>(i)]);
    level.candidate_memo_slot[index] = static_cast<std::int32_t>(level.memo_angle_deg.size());
    level.memo_angle_deg.push_back(level.scratch_angles[static_cast<std::size_t>(i)]);
    Descriptor& descriptor = level.memo_descriptor.emplace_back();
    std::memcpy(descriptor.data(), level.scratch_descriptors.data() + static_cast<std::size_t>(i) * kDescriptorBytes,
                kDescriptorBytes);
  }
}

void FrameAnalysis::describe_through_band(LevelState& level, int count) {
  // The points come in raster order, so the blurred rows they read, [y - kEdgeBorder, y +
  // kEdgeBorder], form a window sliding down the level. The band holds blurred rows [top, end);
  // when a point needs a row below it, the rows still needed move to the band's top and only
  // the new ones are blurred: every blurred row is computed once, in a buffer that stays in cache,
  // and only at the columns the points' patches cover (core/patch_blur.hpp).
  const std::vector<PixelPoint>& points = level.scratch_points;
  std::vector<PixelPoint>& shifted = level.scratch_band_points;
  shifted.resize(static_cast<std::size_t>(count));
  const int width = level.geometry.width, height = level.geometry.height;
  const int capacity = level.blurred.height();
  const MutableImageView band = level.blurred.mutable_view();
  int& top = level.blurred_top;
  int& end = level.blurred_end;
  top = end = 0;
  int first = 0;  // first point not yet described
  const auto describe_up_to = [&](int last) {
    if (last == first) return;
    for (int i = first; i < last; ++i) {
      const PixelPoint& p = points[static_cast<std::size_t>(i)];
      shifted[static_cast<std::size_t>(i)] = {p.x, p.y - top};
    }
    kernels_->rbrief_describe({band.data, width, end - top, band.stride}, shifted.data() + first,
                              level.scratch_angles.data() + first, last - first,
                              level.scratch_descriptors.data() + static_cast<std::size_t>(first) * kDescriptorBytes);
    first = last;
  };
  for (int i = 0; i < count; ++i) {
    const int y = points[static_cast<std::size_t>(i)].y;
    if (y + kEdgeBorder < end) continue;
    describe_up_to(i);
    const int new_top = y - kEdgeBorder;
    const int new_end = std::min(height, new_top + capacity);
    int kept_end = new_top;  // rows [new_top, kept_end) are already blurred in the band
    if (end > new_top) {
      std::memmove(band.data, band.row(new_top - top), static_cast<std::size_t>(end - new_top) * static_cast<std::size_t>(band.stride));
      kept_end = end;
    }
    blur_patch_rows(*kernels_, level.pixels, {band.row(kept_end - new_top), width, new_end - kept_end, band.stride},
                    kept_end, new_end, points.data(), count, level.scratch_blur_columns);
    top = new_top;
    end = new_end;
  }
  describe_up_to(count);
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

std::int64_t FrameAnalysis::level_candidate_count(int n, double threshold) const {
  const LevelState& level = this->level(n);
  std::int64_t total = 0;
  for (int b = 0; b < level.geometry.grid.count(); ++b)
    if (block_kept(n, b, threshold)) total += level.block_candidates[static_cast<std::size_t>(b)].size();
  return total;
}

int FrameAnalysis::level_blocks_kept(int n, double threshold) const {
  int kept = 0;
  for (int b = 0; b < level(n).geometry.grid.count(); ++b) kept += block_kept(n, b, threshold) ? 1 : 0;
  return kept;
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
    const LevelToImage mapping = level_to_image(options_.coordinates, options_.subpixel, scale, width_, height_,
                                                level.geometry.width, level.geometry.height);
    for (std::int32_t i : chosen[static_cast<std::size_t>(n)]) {
      const Candidate& c = level.candidates[static_cast<std::size_t>(i)];
      const std::int32_t slot = level.candidate_memo_slot[static_cast<std::size_t>(i)];
      assert(slot >= 0);
      Keypoint kp;
      const ImagePoint position = keypoint_position(c, mapping);
      kp.x = position.x;
      kp.y = position.y;
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

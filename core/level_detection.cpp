#include "core/level_detection.hpp"

#include <algorithm>
#include <bit>

#include "core/detection_mask.hpp"
#include "core/entropy_fast_threshold.hpp"
#include "core/fast9.hpp"
#include "core/orbslam_cells.hpp"
#include "core/score_band.hpp"

namespace aief {

namespace {

// The candidates of blocks [c_begin, c_end) of block row r, whose scores (with the ring) are in
// the score band from level row score_top.
void detect_run(const PyramidLevel& level, const ExtractorOptions& options,
                const KernelTable& kernels, int r, int c_begin, int c_end, int score_top,
                LevelBlocks& blocks, DetectionScratch& scratch) {
  const BlockGrid& grid = level.geometry.grid;
  const int x_begin = grid.col_edges[static_cast<std::size_t>(c_begin)],
            x_end = grid.col_edges[static_cast<std::size_t>(c_end)];
  const int y0 = grid.row_edges[static_cast<std::size_t>(r)],
            y1 = grid.row_edges[static_cast<std::size_t>(r) + 1];
  const MutableImageView scores = scratch.score_band.mutable_view();
  const bool per_block_threshold = options.fast_threshold_from == FastThresholdFrom::entropy;

  // Local maxima of the score map (threshold-free, see core/fast9.hpp) over the whole run, one
  // bit row per level row, and the strong ones (score >= fast_threshold) likewise, also OR-ed
  // over the rows, which is what the retry rule asks.
  const int words = fast9_maxima_words(x_end - x_begin);
  std::vector<std::uint64_t>& bits = scratch.maxima_bits;
  bits.resize(static_cast<std::size_t>(words) * static_cast<std::size_t>(2 * (y1 - y0) + 1));
  std::uint64_t* strong_any = bits.data();
  std::uint64_t* strong_rows = strong_any + words;
  std::uint64_t* maxima_rows = strong_rows + static_cast<std::ptrdiff_t>(y1 - y0) * words;
  std::fill(strong_any, strong_any + words, std::uint64_t{0});
  const bool masked = level.has_detection_mask();
  if (masked) scratch.allowed_bits.resize(static_cast<std::size_t>(words));
  for (int y = y0; y < y1; ++y) {
    const std::uint8_t* row = scores.row(y - score_top);
    std::uint64_t* strong_row = strong_rows + static_cast<std::ptrdiff_t>(y - y0) * words;
    std::uint64_t* maxima_row = maxima_rows + static_cast<std::ptrdiff_t>(y - y0) * words;
    kernels.fast9_local_maxima_bits(row - scores.stride, row, row + scores.stride, x_begin, x_end,
                                    options.fast_threshold, maxima_row, strong_row);
    if (masked) {  // candidates only where the detection mask allows, before the retry rule
      allowed_bits(level.detection_mask.view().row(y), x_begin, x_end, scratch.allowed_bits.data());
      for (int k = 0; k < words; ++k) {
        maxima_row[k] &= scratch.allowed_bits[static_cast<std::size_t>(k)];
        strong_row[k] &= scratch.allowed_bits[static_cast<std::size_t>(k)];
      }
    }
    for (int k = 0; k < words; ++k) strong_any[k] |= strong_row[k];
  }

  // Each block takes its bit range, in raster order: the strong maxima, or all of them when it
  // has no strong one (ORB-SLAM2's retry rule: fast_threshold, else fast_min_threshold). Reading
  // the strong bit rows skips the weak maxima of a strong block without a compare per maximum.
  std::vector<Candidate>& candidates = blocks.candidates;
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
    for (int k = k_first; k <= k_last; ++k)
      any_strong = any_strong || block_bits(strong_any, k) != 0;
    const std::uint64_t* taken_rows = any_strong ? strong_rows : maxima_rows;
    // FastThresholdFrom::entropy (core/entropy_fast_threshold.hpp): a block with a strong maximum
    // whose entropy lowers its threshold takes its maxima scoring at least that (a superset of
    // the strong ones); without a strong one it retries at fast_min_threshold as before.
    int lowest_score = 0;
    if (per_block_threshold && any_strong) {
      const int threshold =
          entropy_fast_threshold(blocks.entropy_bits[static_cast<std::size_t>(block)], options);
      if (threshold < options.fast_threshold) {
        taken_rows = maxima_rows;
        lowest_score = threshold;
      }
    }
    const bool rank_by_cross = options.candidate_ranking == CandidateRanking::cross_score;
    const std::size_t first = candidates.size();
    const std::ptrdiff_t stride = scores.stride;
    // The cross sum is taken from the scores just read, not reloaded from the stored candidate.
    const auto take = [&](std::uint64_t word, int y, int k) {
      const std::uint8_t* row = scores.row(y - score_top);
      for (; word != 0; word &= word - 1) {
        const int x = x_begin + 64 * k + std::countr_zero(word);
        if (row[x] < lowest_score) continue;
        const std::uint8_t left = row[x - 1], right = row[x + 1], up = row[x - stride],
                           down = row[x + stride];
        candidates.push_back(Candidate{x, y, row[x], left, right, up, down,
                                       rank_by_cross ? left + right + up + down : 0});
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
    blocks.detected[static_cast<std::size_t>(block)] = 1;
    blocks.candidate_range[static_cast<std::size_t>(block)] = {
        static_cast<std::int32_t>(first), static_cast<std::int32_t>(candidates.size())};
  }
}

}  // namespace

void size_detection_scratch(const LevelGeometry& geometry, DetectionScratch& scratch) {
  size_score_band(geometry, scratch.score_band);
}

void detect_kept_blocks(const PyramidLevel& level, BlockMask mask, const ExtractorOptions& options,
                        const KernelTable& kernels, LevelBlocks& blocks,
                        DetectionScratch& scratch) {
  if (!level.usable()) return;
  const BlockGrid& grid = level.geometry.grid;
  if (options.detection_cells == DetectionCells::orbslam) {
    // ORB-SLAM's cells, once for the whole level (FrameAnalysis::start refuses a detection mask),
    // then grouped by block, ORB-SLAM's order kept within each, so the entropy mask and the
    // proportional distribution read block ranges as usual; blocks.orbslam_order keeps the order.
    if (blocks.detected.empty() || blocks.detected[0]) return;
    std::vector<Candidate>& found = scratch.cell_candidates;
    found.clear();
    detect_orbslam_cells(level.detection_pixels, options, kernels, scratch.cells, found);
    std::vector<std::int32_t>& block = scratch.cell_blocks;
    block.resize(found.size());
    for (std::size_t i = 0; i < found.size(); ++i)
      block[i] = block_of(grid, found[i].x, found[i].y);
    std::vector<std::int32_t> starts(static_cast<std::size_t>(grid.count()) + 1, 0);
    for (const std::int32_t b : block) ++starts[static_cast<std::size_t>(b) + 1];
    for (std::size_t b = 1; b < starts.size(); ++b) starts[b] += starts[b - 1];
    for (int b = 0; b < grid.count(); ++b)
      blocks.candidate_range[static_cast<std::size_t>(b)] = {
          starts[static_cast<std::size_t>(b)], starts[static_cast<std::size_t>(b) + 1]};
    blocks.candidates.resize(found.size());
    blocks.orbslam_order.resize(found.size());
    for (std::size_t i = 0; i < found.size(); ++i) {
      const std::int32_t at = starts[static_cast<std::size_t>(block[i])]++;
      blocks.candidates[static_cast<std::size_t>(at)] = found[i];
      blocks.orbslam_order[i] = at;
    }
    std::fill(blocks.detected.begin(), blocks.detected.end(), std::uint8_t{1});
    return;
  }
  const bool masked = level.has_detection_mask();
  if (masked && blocks.allowed.empty())
    blocks_allowed(level.detection_mask.view(), grid, blocks.allowed);
  // A block the detection mask covers whole is never scored: it has no candidate.
  const auto needs = [&](int b) {
    return !blocks.detected[static_cast<std::size_t>(b)] && mask.kept(b) &&
           (!masked || blocks.allowed[static_cast<std::size_t>(b)]);
  };

  // Scores of each run of adjacent new blocks in a block row, with the one-pixel ring that
  // suppression reads, go to the score band: one call per row of the run instead of a call per
  // ring segment, then the run's blocks.
  for (int r = 0; r < grid.rows(); ++r) {
    const int score_top = grid.row_edges[static_cast<std::size_t>(r)] - 1;
    int c = 0;
    while (c < grid.cols()) {
      if (!needs(r * grid.cols() + c)) {
        ++c;
        continue;
      }
      int end = c;
      while (end < grid.cols() && needs(r * grid.cols() + end)) ++end;
      compute_score_rows(level.detection_pixels, kernels, options.fast_min_threshold,
                         scratch.score_band, score_top, score_top,
                         grid.row_edges[static_cast<std::size_t>(r) + 1] + 1,
                         grid.col_edges[static_cast<std::size_t>(c)] - 1,
                         grid.col_edges[static_cast<std::size_t>(end)] + 1);
      detect_run(level, options, kernels, r, c, end, score_top, blocks, scratch);
      c = end;
    }
  }
}

}  // namespace aief

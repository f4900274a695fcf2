#include "core/detection/level_detection.hpp"

#include <algorithm>
#include <bit>

#include "core/detection/orbslam_cells.hpp"
#include "core/detection/score_band.hpp"
#include "core/entropy/entropy_fast_threshold.hpp"
#include "core/kernels/fast9_scores_row.hpp"
#include "core/level/caller_mask.hpp"

namespace aief {

namespace {

// The score rows of a run of blocks: row(dy) is level row y0 + dy, at x = x_begin.
struct RunScores {
  const std::uint8_t* first_row;
  std::ptrdiff_t stride;
  int x_begin, y0;
  const std::uint8_t* row(int dy) const { return first_row + dy * stride; }
};

// The candidates of one bit word of row dy (bit i: x = x_begin + x0 + i), in raster order, those
// scoring at least lowest_score; rank_extra is the cross sum AND cross_mask. Each is written,
// then kept by advancing `out` or not: no branch per candidate but the loop's. The cross sum is
// taken from the scores just read, not reloaded from the stored candidate. Returns the new end.
inline Candidate* write_word_candidates(std::uint64_t word, int x0, int dy, RunScores scores,
                                        int lowest_score, std::int32_t cross_mask, Candidate* out) {
  const std::uint8_t* row = scores.row(dy) + x0;
  const int x = scores.x_begin + x0, y = scores.y0 + dy;
  for (; word != 0; word &= word - 1) {
    const int bit = std::countr_zero(word);
    const std::uint8_t* at = row + bit;
    const std::uint8_t score = at[0], left = at[-1], right = at[1], up = at[-scores.stride],
                       down = at[scores.stride];
    *out = Candidate{x + bit, y,  score, left,
                     right,   up, down,  (left + right + up + down) & cross_mask};
    out += score >= lowest_score;
  }
  return out;
}

// Bits [begin, end) of a row of bit words: the words k_first..k_last, masked.
struct BitRange {
  int k_first, k_last;
  std::uint64_t first_mask, last_mask;
  BitRange(int begin, int end)
      : k_first(begin / 64),
        k_last((end - 1) / 64),
        first_mask(~std::uint64_t{0} << (begin % 64)),
        last_mask(~std::uint64_t{0} >> (63 - (end - 1) % 64)) {}
  std::uint64_t word(const std::uint64_t* row_words, int k) const {
    std::uint64_t word = row_words[k];
    if (k == k_first) word &= first_mask;
    if (k == k_last) word &= last_mask;
    return word;
  }
};

// The candidates of one block: bits [begin, end) of its `rows` rows of bit words, `words` apart
// from taken_rows. Writes at most rows * ((end - begin + 1) / 2) of them (strict maxima are never
// adjacent) and returns the new end. The rows that hold a maximum are found first, as the bits
// of a word (64 rows at a time), and only those are walked: whether a row of a block holds one is
// close to a coin toss, and a branch per row mispredicted 11,000 of its 41,000 tests on graf
// (valgrind's branch model, docs/speed.md). Not inlined into detect_run: with its own registers
// the candidate loop keeps its values out of the stack.
[[gnu::noinline]] Candidate* write_block_candidates(const std::uint64_t* taken_rows, int words,
                                                    int rows, int begin, int end, RunScores scores,
                                                    int lowest_score, std::int32_t cross_mask,
                                                    Candidate* out) {
  const BitRange range(begin, end);
  const int k_first = range.k_first, k_last = range.k_last;
  const auto word_at = [&](int dy, int k) {
    return range.word(taken_rows + static_cast<std::ptrdiff_t>(dy) * words, k);
  };
  for (int dy0 = 0; dy0 < rows; dy0 += 64) {
    const int chunk = std::min(64, rows - dy0);
    std::uint64_t nonempty = 0;  // bit i: row dy0 + i holds a maximum
    if (k_first == k_last) {     // the usual block, inside one word: one masked word per row
      const std::uint64_t mask = range.first_mask & range.last_mask;
      const std::uint64_t* first = taken_rows + static_cast<std::ptrdiff_t>(dy0) * words + k_first;
      // From the chunk's last row up, doubling: no variable shift (9 instructions a row).
      for (std::ptrdiff_t at = static_cast<std::ptrdiff_t>(chunk - 1) * words; at >= 0; at -= words)
        nonempty = 2 * nonempty + std::uint64_t{(first[at] & mask) != 0};
      for (; nonempty != 0; nonempty &= nonempty - 1) {
        const int dy = dy0 + std::countr_zero(nonempty);
        out = write_word_candidates(word_at(dy, k_first), 64 * k_first, dy, scores, lowest_score,
                                    cross_mask, out);
      }
    } else {
      for (int i = 0; i < chunk; ++i) {
        std::uint64_t any = 0;
        for (int k = k_first; k <= k_last; ++k) any |= word_at(dy0 + i, k);
        nonempty |= std::uint64_t{any != 0} << i;
      }
      for (; nonempty != 0; nonempty &= nonempty - 1) {
        const int dy = dy0 + std::countr_zero(nonempty);
        for (int k = k_first; k <= k_last; ++k)
          out = write_word_candidates(word_at(dy, k), 64 * k, dy, scores, lowest_score, cross_mask,
                                      out);
      }
    }
  }
  return out;
}

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

  // Local maxima of the score map (threshold-free, see core/kernels/fast9_scores_row.hpp) over the
  // whole run, one bit row per level row, and the strong ones (score >= fast_threshold) likewise,
  // also OR-ed over the rows, which is what the retry rule asks.
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
  std::vector<Candidate>& written = scratch.run_candidates;
  const std::size_t first = candidates.size();
  std::size_t used = 0;  // of `written`, by the run's blocks so far
  const std::int32_t cross_mask =
      options.candidate_ranking == CandidateRanking::cross_score ? ~std::int32_t{0} : 0;
  const RunScores run_scores{scores.row(y0 - score_top) + x_begin, scores.stride, x_begin, y0};
  for (int c = c_begin; c < c_end; ++c) {
    const int block = r * grid.cols() + c;
    const int begin = grid.col_edges[static_cast<std::size_t>(c)] - x_begin;
    const int end = grid.col_edges[static_cast<std::size_t>(c) + 1] - x_begin;
    const BitRange range(begin, end);
    bool any_strong = false;
    for (int k = range.k_first; k <= range.k_last; ++k)
      any_strong = any_strong || range.word(strong_any, k) != 0;
    const std::uint64_t* taken_rows = any_strong ? strong_rows : maxima_rows;
    // FastThresholdFrom::entropy (core/entropy/entropy_fast_threshold.hpp): a block with a strong
    // maximum whose entropy lowers its threshold takes its maxima scoring at least that (a superset
    // of the strong ones); without a strong one it retries at fast_min_threshold as before.
    int lowest_score = 0;
    if (per_block_threshold && any_strong) {
      const int threshold =
          entropy_fast_threshold(blocks.entropy_bits[static_cast<std::size_t>(block)], options);
      if (threshold < options.fast_threshold) {
        taken_rows = maxima_rows;
        lowest_score = threshold;
      }
    }
    const std::size_t most =
        used + static_cast<std::size_t>(y1 - y0) * static_cast<std::size_t>((end - begin + 1) / 2);
    if (written.size() < most) written.resize(most);
    const std::size_t block_end = static_cast<std::size_t>(
        write_block_candidates(taken_rows, words, y1 - y0, begin, end, run_scores, lowest_score,
                               cross_mask, written.data() + used) -
        written.data());
    blocks.detected[static_cast<std::size_t>(block)] = 1;
    blocks.candidate_range[static_cast<std::size_t>(block)] = {
        static_cast<std::int32_t>(first + used), static_cast<std::int32_t>(first + block_end)};
    used = block_end;
  }
  candidates.insert(candidates.end(), written.begin(),
                    written.begin() + static_cast<std::ptrdiff_t>(used));
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

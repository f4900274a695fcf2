#include "core/distribution/candidate_pool.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace aief {

namespace {

constexpr int kScoreLevels = 256;  // FAST scores are bytes
constexpr int kStrengthLevels =
    5 * kScoreLevels;  // rank_strength(): at most five scores (the cross)

// Order of candidates of equal strength, as stronger() ranks them: higher score, then y, then x
// (a level is narrower and shorter than 2^25 pixels: max_image_pixels <= 2^26).
std::int64_t tie_key(const Candidate& c) {
  return (static_cast<std::int64_t>(kScoreLevels - 1 - c.score) << 50) |
         (static_cast<std::int64_t>(c.y) << 25) | static_cast<std::int64_t>(c.x);
}

}  // namespace

std::int64_t candidate_pool_size(double pool_factor, int n_wanted) {
  if (!std::isfinite(pool_factor)) return -1;
  const double size = std::ceil(pool_factor * static_cast<double>(n_wanted));
  if (size >= static_cast<double>(std::numeric_limits<std::int32_t>::max())) return -1;
  return std::max<std::int64_t>(static_cast<std::int64_t>(size), n_wanted);
}

void pool_candidates(const std::vector<Candidate>& candidates,
                     const std::vector<BlockRange>& blocks, std::int64_t pool_size,
                     std::vector<Candidate>& pooled, std::vector<std::int32_t>& pooled_index,
                     std::vector<BlockRange>& pooled_blocks, CandidatePoolScratch& scratch) {
  assert(pool_size >= 0);
  pooled.clear();
  pooled_index.clear();
  pooled_blocks.clear();
  if (pool_size == 0) return;

  // The kept blocks' ranges merged where they touch (detection writes blocks in order, so a
  // frame's kept blocks are usually one range): the passes below run over a few long ranges,
  // not a short loop per block whose exit mispredicts.
  std::vector<BlockRange>& spans = scratch.spans;
  spans.clear();
  for (const BlockRange& block : blocks) {
    if (block.size() == 0) continue;
    if (!spans.empty() && spans.back().end == block.begin)
      spans.back().end = block.end;
    else
      spans.push_back(block);
  }

  // The cut-off: the strength s of the pool_size-th strongest candidate, found by counting
  // strengths (exact, whatever the order); of the candidates at s, the first ones in tie_key()
  // order fill the pool, as stronger() ranks them.
  std::array<std::int32_t, kStrengthLevels> count_at{};  // candidates < 2^31
  std::int64_t total = 0;
  for (const BlockRange& span : spans) {
    for (std::int32_t i = span.begin; i < span.end; ++i) {
      const Candidate& c = candidates[static_cast<std::size_t>(i)];
      assert(c.score >= 0 && c.score < kScoreLevels && c.x >= 0 && c.x < (1 << 25) && c.y >= 0 &&
             c.y < (1 << 25));
      const int strength = rank_strength(c);
      assert(strength >= 0 && strength < kStrengthLevels);
      ++count_at[static_cast<std::size_t>(strength)];
    }
    total += span.size();
  }
  int cut_strength = -1;  // keep every strength above it
  std::int64_t key_limit =
      std::numeric_limits<std::int64_t>::max();  // at cut_strength: keys <= limit
  if (total > pool_size) {
    std::int64_t above = 0;
    cut_strength = kStrengthLevels - 1;
    while (above + count_at[static_cast<std::size_t>(cut_strength)] < pool_size)
      above += count_at[static_cast<std::size_t>(cut_strength--)];
    const std::int64_t tied_wanted = pool_size - above;  // 0 < tied_wanted <= count at cut_strength
    std::vector<std::int32_t>& tied = scratch.tied;
    tied.clear();
    for (const BlockRange& span : spans)
      for (std::int32_t i = span.begin; i < span.end; ++i)
        if (rank_strength(candidates[static_cast<std::size_t>(i)]) == cut_strength)
          tied.push_back(i);
    const auto by_tie_key = [&](std::int32_t a, std::int32_t b) {
      return tie_key(candidates[static_cast<std::size_t>(a)]) <
             tie_key(candidates[static_cast<std::size_t>(b)]);
    };
    std::nth_element(tied.begin(), tied.begin() + (tied_wanted - 1), tied.end(), by_tie_key);
    key_limit = tie_key(
        candidates[static_cast<std::size_t>(tied[static_cast<std::size_t>(tied_wanted - 1)])]);
  }

  // The copy, without a branch per candidate: each is written, then kept by advancing the write
  // place or not (whether a candidate makes the pool is close to a coin toss near the cut-off).
  // How many were kept before and after each candidate give each block's range in the pool
  // without a loop per block (blocks are ranges of the candidates, not always in their order).
  const std::int64_t kept = std::min(total, pool_size);
  pooled.resize(static_cast<std::size_t>(kept) + 1);  // + 1: the last write may not be kept
  pooled_index.resize(static_cast<std::size_t>(kept) + 1);
  std::int32_t lowest = std::numeric_limits<std::int32_t>::max(), highest = 0;
  for (const BlockRange& span : spans) {
    lowest = std::min(lowest, span.begin);
    highest = std::max(highest, span.end);
  }
  std::vector<std::int32_t>& kept_before = scratch.kept_before;
  std::vector<std::int32_t>& kept_after = scratch.kept_after;
  kept_before.resize(static_cast<std::size_t>(std::max(0, highest - lowest)));
  kept_after.resize(kept_before.size());
  Candidate* out = pooled.data();
  std::int32_t* out_index = pooled_index.data();
  std::int32_t n = 0;
  for (const BlockRange& span : spans)
    for (std::int32_t i = span.begin; i < span.end; ++i) {
      const Candidate& c = candidates[static_cast<std::size_t>(i)];
      const int strength = rank_strength(c);
      kept_before[static_cast<std::size_t>(i - lowest)] = n;
      out[n] = c;
      out_index[n] = i;
      n += static_cast<std::int32_t>(strength > cut_strength) |
           static_cast<std::int32_t>(strength == cut_strength && tie_key(c) <= key_limit);
      kept_after[static_cast<std::size_t>(i - lowest)] = n;
    }
  assert(n == kept);
  pooled.resize(static_cast<std::size_t>(n));
  pooled_index.resize(static_cast<std::size_t>(n));
  pooled_blocks.resize(blocks.size() + 1);
  std::size_t nonempty = 0;
  for (const BlockRange& block : blocks) {
    if (block.size() == 0) continue;
    const BlockRange range{kept_before[static_cast<std::size_t>(block.begin - lowest)],
                           kept_after[static_cast<std::size_t>(block.end - 1 - lowest)]};
    pooled_blocks[nonempty] = range;
    nonempty += range.size() > 0;
  }
  pooled_blocks.resize(nonempty);
}

}  // namespace aief

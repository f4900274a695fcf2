#include "core/candidate_pool.hpp"

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

  // The cut-off: the strength s of the pool_size-th strongest candidate, found by counting
  // strengths (exact, whatever the order); of the candidates at s, the first ones in tie_key()
  // order fill the pool, as stronger() ranks them.
  std::array<std::int64_t, kStrengthLevels> count_at{};
  std::int64_t total = 0;
  for (const BlockRange& block : blocks)
    for (std::int32_t i = block.begin; i < block.end; ++i) {
      const Candidate& c = candidates[static_cast<std::size_t>(i)];
      assert(c.score >= 0 && c.score < kScoreLevels && c.x >= 0 && c.x < (1 << 25) && c.y >= 0 &&
             c.y < (1 << 25));
      const int strength = rank_strength(c);
      assert(strength >= 0 && strength < kStrengthLevels);
      ++count_at[static_cast<std::size_t>(strength)];
      ++total;
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
    for (const BlockRange& block : blocks)
      for (std::int32_t i = block.begin; i < block.end; ++i)
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

  for (const BlockRange& block : blocks) {
    const std::int32_t first = static_cast<std::int32_t>(pooled.size());
    for (std::int32_t i = block.begin; i < block.end; ++i) {
      const Candidate& c = candidates[static_cast<std::size_t>(i)];
      const int strength = rank_strength(c);
      if (strength < cut_strength || (strength == cut_strength && tie_key(c) > key_limit)) continue;
      pooled.push_back(c);
      pooled_index.push_back(i);
    }
    const std::int32_t end = static_cast<std::int32_t>(pooled.size());
    if (end > first) pooled_blocks.push_back({first, end});
  }
  assert(total <= pool_size || static_cast<std::int64_t>(pooled.size()) == pool_size);
}

}  // namespace aief

#include "core/candidate_pool.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace aief {

namespace {

constexpr int kScoreLevels = 256;  // FAST scores are bytes

std::int64_t position_key(const Candidate& c) {
  return (static_cast<std::int64_t>(c.y) << 32) | static_cast<std::int64_t>(static_cast<std::uint32_t>(c.x));
}

}  // namespace

std::int64_t candidate_pool_size(double pool_factor, int n_wanted) {
  if (!std::isfinite(pool_factor)) return -1;
  const double size = std::ceil(pool_factor * static_cast<double>(n_wanted));
  if (size >= static_cast<double>(std::numeric_limits<std::int32_t>::max())) return -1;
  return std::max<std::int64_t>(static_cast<std::int64_t>(size), n_wanted);
}

void pool_candidates(const std::vector<Candidate>& candidates, const std::vector<BlockRange>& blocks,
                     std::int64_t pool_size, std::vector<Candidate>& pooled, std::vector<std::int32_t>& pooled_index,
                     std::vector<BlockRange>& pooled_blocks, CandidatePoolScratch& scratch) {
  assert(pool_size >= 0);
  pooled.clear();
  pooled_index.clear();
  pooled_blocks.clear();
  if (pool_size == 0) return;

  // The cut-off: the score s of the pool_size-th strongest candidate, found by counting scores
  // (exact, whatever the order); of the candidates at s, the first ones in (y, x) order fill the
  // pool, as stronger() ranks them.
  std::array<std::int64_t, kScoreLevels> count_at{};
  std::int64_t total = 0;
  for (const BlockRange& block : blocks)
    for (std::int32_t i = block.begin; i < block.end; ++i) {
      const int score = candidates[static_cast<std::size_t>(i)].score;
      assert(score >= 0 && score < kScoreLevels);
      ++count_at[static_cast<std::size_t>(score)];
      ++total;
    }
  int cut_score = -1;                                        // keep every score above it
  std::int64_t key_limit = std::numeric_limits<std::int64_t>::max();  // at cut_score: keys <= limit
  if (total > pool_size) {
    std::int64_t above = 0;
    cut_score = kScoreLevels - 1;
    while (above + count_at[static_cast<std::size_t>(cut_score)] < pool_size) above += count_at[static_cast<std::size_t>(cut_score--)];
    const std::int64_t tied_wanted = pool_size - above;  // 0 < tied_wanted <= count at cut_score
    std::vector<std::int32_t>& tied = scratch.tied;
    tied.clear();
    for (const BlockRange& block : blocks)
      for (std::int32_t i = block.begin; i < block.end; ++i)
        if (candidates[static_cast<std::size_t>(i)].score == cut_score) tied.push_back(i);
    const auto by_position = [&](std::int32_t a, std::int32_t b) {
      return position_key(candidates[static_cast<std::size_t>(a)]) < position_key(candidates[static_cast<std::size_t>(b)]);
    };
    std::nth_element(tied.begin(), tied.begin() + (tied_wanted - 1), tied.end(), by_position);
    key_limit = position_key(candidates[static_cast<std::size_t>(tied[static_cast<std::size_t>(tied_wanted - 1)])]);
  }

  for (const BlockRange& block : blocks) {
    const std::int32_t first = static_cast<std::int32_t>(pooled.size());
    for (std::int32_t i = block.begin; i < block.end; ++i) {
      const Candidate& c = candidates[static_cast<std::size_t>(i)];
      if (c.score < cut_score || (c.score == cut_score && position_key(c) > key_limit)) continue;
      pooled.push_back(c);
      pooled_index.push_back(i);
    }
    const std::int32_t end = static_cast<std::int32_t>(pooled.size());
    if (end > first) pooled_blocks.push_back({first, end});
  }
  assert(total <= pool_size || static_cast<std::int64_t>(pooled.size()) == pool_size);
}

}  // namespace aief

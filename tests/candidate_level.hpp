#pragma once
// A pyramid level's candidates made up for the distribution and pool tests: blocks of 32 x 32
// pixels side by side, block i holding counts[i] candidates at distinct random positions, with
// scores from a small range so that ties (and so the tie-break) are common.
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/distribution/candidate.hpp"
#include "core/distribution/distribution.hpp"

namespace aief::test {

struct CandidateLevel {
  std::vector<Candidate> candidates;  // block by block, raster order within a block
  std::vector<BlockRange> blocks;
};

// Scores are 7 + a uniform draw below `score_values`; reproducible from the seed.
inline CandidateLevel make_candidate_level(const std::vector<int>& counts, std::uint32_t seed,
                                           int score_values) {
  CandidateLevel level;
  std::mt19937 rng(seed);
  for (std::size_t b = 0; b < counts.size(); ++b) {
    const auto begin = static_cast<std::int32_t>(level.candidates.size());
    std::set<std::pair<int, int>> used;  // (y, x)
    while (static_cast<int>(used.size()) < counts[b]) {
      const int x = static_cast<int>(b) * 32 + static_cast<int>(rng() % 32),
                y = static_cast<int>(rng() % 32);
      used.insert({y, x});
    }
    for (const auto& [y, x] : used)
      level.candidates.push_back(candidate_at(
          x, y, 7 + static_cast<int>(rng() % static_cast<std::uint32_t>(score_values))));
    level.blocks.push_back({begin, static_cast<std::int32_t>(level.candidates.size())});
  }
  return level;
}

}  // namespace aief::test

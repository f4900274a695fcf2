// Proportional (AIEF) and quadtree (ORB-SLAM2) distribution of one level's candidates.
#include <algorithm>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/distribution/distribution.hpp"
#include "tests/candidate_level.hpp"

namespace aief {
namespace {

using Level = test::CandidateLevel;

// Scores 7..26: ties are common, so the tie-break is exercised.
Level make_level(const std::vector<int>& counts, std::uint32_t seed) {
  return test::make_candidate_level(counts, seed, 20);
}

std::map<int, std::vector<std::int32_t>> kept_per_block(const Level& level,
                                                        const std::vector<std::int32_t>& selected) {
  std::map<int, std::vector<std::int32_t>> per_block;
  for (std::int32_t index : selected)
    for (std::size_t b = 0; b < level.blocks.size(); ++b)
      if (index >= level.blocks[b].begin && index < level.blocks[b].end)
        per_block[static_cast<int>(b)].push_back(index);
  return per_block;
}

TEST(ProportionalDistribution, KeepsExactlyTheWantedCountWithAWaterLevel) {
  const std::vector<std::vector<int>> layouts = {{0, 1, 2, 50, 50, 3, 40, 0, 9},
                                                 {10, 10, 10, 10},
                                                 {100},
                                                 {1, 1, 1, 1, 200},
                                                 {5, 17, 33, 2, 0, 64, 12}};
  for (std::size_t l = 0; l < layouts.size(); ++l) {
    const Level level = make_level(layouts[l], static_cast<std::uint32_t>(l));
    int total = 0;
    for (int count : layouts[l]) total += count;
    DistributionScratch scratch;
    for (int wanted : {0, 1, 3, 7, 20, 35, 61, total - 1, total, total + 10}) {
      if (wanted < 0) continue;
      std::vector<std::int32_t> selected;
      distribute_proportional(level.candidates, level.blocks, wanted, selected, scratch);
      SCOPED_TRACE(testing::Message() << "layout " << l << ", wanted " << wanted);
      ASSERT_EQ(static_cast<int>(selected.size()), std::min(wanted, total));
      EXPECT_EQ(std::set<std::int32_t>(selected.begin(), selected.end()).size(), selected.size())
          << "duplicates";

      const auto per_block = kept_per_block(level, selected);
      int most = 0;
      for (const auto& [block, kept] : per_block)
        most = std::max(most, static_cast<int>(kept.size()));
      for (std::size_t b = 0; b < level.blocks.size(); ++b) {
        const int available = level.blocks[b].size();
        const auto it = per_block.find(static_cast<int>(b));
        const int kept = it == per_block.end() ? 0 : static_cast<int>(it->second.size());
        // Water level: every block keeps min(R_i, k) or k + 1, with k + 1 == most.
        EXPECT_GE(kept, std::min(available, most - 1))
            << "block " << b << " starved below the water level";
        if (available < most) {
          EXPECT_EQ(kept, available) << "block " << b << " under the level must keep all";
        }
        // The kept ones are the block's strongest.
        if (it != per_block.end()) {
          const Candidate* weakest_kept = nullptr;
          for (std::int32_t i : it->second)
            if (!weakest_kept ||
                stronger(*weakest_kept, level.candidates[static_cast<std::size_t>(i)]))
              weakest_kept = &level.candidates[static_cast<std::size_t>(i)];
          const std::set<std::int32_t> kept_set(it->second.begin(), it->second.end());
          for (std::int32_t i = level.blocks[b].begin; i < level.blocks[b].end; ++i)
            if (!kept_set.count(i)) {
              EXPECT_FALSE(stronger(level.candidates[static_cast<std::size_t>(i)], *weakest_kept))
                  << "block " << b << " dropped candidate " << i << " stronger than one it kept";
            }
        }
      }
    }
  }
}

TEST(ProportionalDistribution, ReproducesThePapersIterativeAllocation) {
  // The paper's loop: give k = rest / blocks to each block still wanting, hand back what a block
  // cannot use, repeat. Its totals per block must equal ours (up to the final fractions).
  const Level level = make_level({3, 40, 8, 0, 25, 12, 6, 30}, 99);
  const int wanted = 60;
  std::vector<int> allocated(level.blocks.size(), 0);
  int rest = wanted;
  while (rest > 0) {
    std::vector<std::size_t> hungry;
    for (std::size_t b = 0; b < level.blocks.size(); ++b)
      if (allocated[b] < level.blocks[b].size()) hungry.push_back(b);
    if (hungry.empty()) break;
    const int share = rest / static_cast<int>(hungry.size());
    if (share == 0) break;
    for (std::size_t b : hungry) {
      const int give = std::min(share, level.blocks[b].size() - allocated[b]);
      allocated[b] += give;
      rest -= give;
    }
  }
  std::vector<std::int32_t> selected;
  DistributionScratch scratch;
  distribute_proportional(level.candidates, level.blocks, wanted, selected, scratch);
  const auto per_block = kept_per_block(level, selected);
  for (std::size_t b = 0; b < level.blocks.size(); ++b) {
    const auto it = per_block.find(static_cast<int>(b));
    const int kept = it == per_block.end() ? 0 : static_cast<int>(it->second.size());
    EXPECT_GE(kept, allocated[b]) << "block " << b;
    EXPECT_LE(kept, allocated[b] + 1) << "block " << b;
  }
}

TEST(QuadtreeDistribution, CountsAsOrbSlam2AndDeterministic) {
  std::mt19937 rng(7);
  DistributionScratch scratch;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Candidate> candidates;
    std::set<std::pair<int, int>> used;
    const int count = 1 + static_cast<int>(rng() % 600);
    const int width = 60 + static_cast<int>(rng() % 800),
              height = 60 + static_cast<int>(rng() % 600);
    while (static_cast<int>(used.size()) < count) {
      const int x = 19 + static_cast<int>(rng() % static_cast<unsigned>(width - 38));
      const int y = 19 + static_cast<int>(rng() % static_cast<unsigned>(height - 38));
      if (used.insert({x, y}).second)
        candidates.push_back(candidate_at(x, y, 7 + static_cast<int>(rng() % 5)));
    }
    for (int wanted : {1, 5, 50, 217, 1000}) {
      std::vector<std::int32_t> first, second;
      distribute_quadtree(candidates, 16, width - 16, 16, height - 16, wanted, first, scratch);
      ASSERT_EQ(static_cast<int>(first.size()), std::min(wanted, count))
          << "trial " << trial << " wanted " << wanted;
      EXPECT_EQ(std::set<std::int32_t>(first.begin(), first.end()).size(), first.size());
      // Same candidates in another order: the same points.
      std::vector<std::size_t> order(candidates.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), rng);
      std::vector<Candidate> shuffled;
      for (std::size_t i : order) shuffled.push_back(candidates[i]);
      distribute_quadtree(shuffled, 16, width - 16, 16, height - 16, wanted, second, scratch);
      std::set<std::pair<int, int>> a, b;
      for (std::int32_t i : first)
        a.insert(
            {candidates[static_cast<std::size_t>(i)].x, candidates[static_cast<std::size_t>(i)].y});
      for (std::int32_t i : second)
        b.insert(
            {shuffled[static_cast<std::size_t>(i)].x, shuffled[static_cast<std::size_t>(i)].y});
      EXPECT_EQ(a, b) << "trial " << trial << ": result depends on the input order";
    }
  }
}

TEST(QuadtreeDistribution, OneWantedKeepsTheStrongest) {
  std::vector<Candidate> candidates = {candidate_at(30, 30, 10), candidate_at(200, 40, 50),
                                       candidate_at(100, 100, 20)};
  std::vector<std::int32_t> selected;
  DistributionScratch scratch;
  distribute_quadtree(candidates, 16, 300, 16, 200, 1, selected, scratch);
  ASSERT_EQ(selected.size(), 1u);
  EXPECT_EQ(selected[0], 1);
}

}  // namespace
}  // namespace aief

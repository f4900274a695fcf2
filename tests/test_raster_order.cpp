// Raster order of a level's selected candidates: the radix sort and the rank sort against
// std::sort by raster_before, on levels whose places need one to four bytes.
#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/distribution/raster_order.hpp"

namespace aief {
namespace {

struct Level {
  int width, height;
  std::vector<Candidate> candidates;  // distinct positions, in no order
};

Level random_level(int width, int height, int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Level level{width, height, {}};
  std::set<std::pair<int, int>> used;
  while (static_cast<int>(level.candidates.size()) < count) {
    const int x = static_cast<int>(rng() % static_cast<std::uint32_t>(width));
    const int y = static_cast<int>(rng() % static_cast<std::uint32_t>(height));
    if (used.insert({x, y}).second) level.candidates.push_back(candidate_at(x, y, 20));
  }
  return level;
}

// Every other candidate, shuffled: a selection.
std::vector<std::int32_t> some_indices(const Level& level, std::uint32_t seed) {
  std::vector<std::int32_t> indices;
  for (std::size_t i = 0; i < level.candidates.size(); i += 2)
    indices.push_back(static_cast<std::int32_t>(i));
  std::shuffle(indices.begin(), indices.end(), std::mt19937(seed));
  return indices;
}

std::vector<std::int32_t> by_raster_before(const Level& level, std::vector<std::int32_t> indices) {
  std::sort(indices.begin(), indices.end(), [&](std::int32_t a, std::int32_t b) {
    return raster_before(level.candidates[static_cast<std::size_t>(a)],
                         level.candidates[static_cast<std::size_t>(b)]);
  });
  return indices;
}

TEST(RasterOrder, BothSortsEqualRasterBeforeFromOneToFourBytesOfPlace) {
  // Places below 2^8, 2^16, 2^24 and up to 2^26 (the largest level max_image_pixels allows).
  const std::vector<std::pair<int, int>> sizes = {{15, 16}, {200, 300}, {4000, 4000}, {8192, 8192}};
  std::uint32_t seed = 1;
  for (const auto& [width, height] : sizes)
    for (const int count : {0, 1, 2, 37, 1000}) {
      if (count > width * height / 2) continue;
      const Level level = random_level(width, height, count, seed++);
      const std::vector<std::int32_t> indices = some_indices(level, seed++);
      const std::vector<std::int32_t> expected = by_raster_before(level, indices);
      RasterRanks ranks;
      std::vector<std::int32_t> radix = indices;
      sort_in_raster_order(level.candidates, width, radix, ranks);
      EXPECT_EQ(radix, expected) << width << " x " << height << ", " << count << " candidates";
      std::vector<std::int32_t> ranked = indices;
      sort_by_raster_rank(level.candidates, width, height, ranks, ranked);
      EXPECT_EQ(ranked, expected) << width << " x " << height << ", " << count << " candidates";
    }
}

}  // namespace
}  // namespace aief

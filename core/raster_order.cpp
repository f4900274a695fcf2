#include "core/raster_order.hpp"

#include <algorithm>
#include <bit>

namespace aief {

namespace {

// Candidate indices in raster order (y, then x; positions are distinct): a counting sort by x,
// then a stable one by y, linear in the candidates and the level's size.
void build_raster_ranks(const std::vector<Candidate>& candidates, int width, int height,
                        RasterRanks& ranks) {
  const std::size_t count = candidates.size();
  std::vector<std::int32_t>& by_x = ranks.rank;  // scratch until the end
  std::vector<std::int32_t>& order = ranks.order;
  by_x.resize(count);
  order.resize(count);
  std::vector<std::int32_t>& starts = ranks.counting_starts;
  const auto counting_pass = [&](const std::vector<std::int32_t>* input,
                                 std::vector<std::int32_t>& output, int extent, auto key) {
    starts.assign(static_cast<std::size_t>(extent) + 1, 0);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = input ? static_cast<std::size_t>((*input)[k]) : k;
      ++starts[static_cast<std::size_t>(key(candidates[i])) + 1];
    }
    for (int v = 0; v < extent; ++v)
      starts[static_cast<std::size_t>(v) + 1] += starts[static_cast<std::size_t>(v)];
    for (std::size_t k = 0; k < count; ++k) {
      const std::int32_t i = input ? (*input)[k] : static_cast<std::int32_t>(k);
      output[static_cast<std::size_t>(
          starts[static_cast<std::size_t>(key(candidates[static_cast<std::size_t>(i)]))]++)] = i;
    }
  };
  counting_pass(nullptr, by_x, width, [](const Candidate& c) { return c.x; });
  counting_pass(&by_x, order, height, [](const Candidate& c) { return c.y; });
  std::vector<std::int32_t>& rank = ranks.rank;
  for (std::size_t r = 0; r < count; ++r)
    rank[static_cast<std::size_t>(order[r])] = static_cast<std::int32_t>(r);
}

}  // namespace

void sort_in_raster_order(const std::vector<Candidate>& candidates,
                          std::vector<std::int32_t>& indices) {
  std::sort(indices.begin(), indices.end(), [&](std::int32_t a, std::int32_t b) {
    return raster_before(candidates[static_cast<std::size_t>(a)],
                         candidates[static_cast<std::size_t>(b)]);
  });
}

void sort_by_raster_rank(const std::vector<Candidate>& candidates, int width, int height,
                         RasterRanks& ranks, std::vector<std::int32_t>& indices) {
  if (ranks.rank.size() != candidates.size()) build_raster_ranks(candidates, width, height, ranks);
  std::vector<std::uint64_t>& bits = ranks.place_bits;
  bits.assign((candidates.size() + 63) / 64, 0);
  for (std::int32_t i : indices) {
    const std::int32_t rank = ranks.rank[static_cast<std::size_t>(i)];
    bits[static_cast<std::size_t>(rank) / 64] |= std::uint64_t{1} << (rank % 64);
  }
  indices.clear();
  for (std::size_t w = 0; w < bits.size(); ++w)
    for (std::uint64_t word = bits[w]; word != 0; word &= word - 1)
      indices.push_back(ranks.order[w * 64 + static_cast<std::size_t>(std::countr_zero(word))]);
}

}  // namespace aief

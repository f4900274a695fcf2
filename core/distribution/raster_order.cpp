#include "core/distribution/raster_order.hpp"

#include <algorithm>
#include <array>
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

void sort_in_raster_order(const std::vector<Candidate>& candidates, int width,
                          std::vector<std::int32_t>& indices, RasterRanks& ranks) {
  const std::size_t count = indices.size();
  std::vector<std::uint64_t>& keys = ranks.radix_keys;
  keys.resize(2 * count);
  std::uint64_t* from = keys.data();
  std::uint64_t* to = from + count;
  std::uint64_t places = 0;  // every place OR-ed: how many bytes the passes need
  for (std::size_t k = 0; k < count; ++k) {
    const Candidate& c = candidates[static_cast<std::size_t>(indices[k])];
    const std::uint64_t place =
        static_cast<std::uint64_t>(c.y) * static_cast<std::uint64_t>(width) +
        static_cast<std::uint64_t>(c.x);
    places |= place;
    from[k] = place << 32 | static_cast<std::uint32_t>(indices[k]);
  }
  // Least significant byte first, each pass a stable counting sort: places are distinct, so the
  // order is raster_before's.
  for (int shift = 32; shift < 64 && (places >> (shift - 32)) != 0; shift += 8) {
    std::array<std::uint32_t, 257> starts{};
    for (std::size_t k = 0; k < count; ++k) ++starts[((from[k] >> shift) & 255) + 1];
    for (int b = 0; b < 256; ++b)
      starts[static_cast<std::size_t>(b) + 1] += starts[static_cast<std::size_t>(b)];
    for (std::size_t k = 0; k < count; ++k) to[starts[(from[k] >> shift) & 255]++] = from[k];
    std::swap(from, to);
  }
  for (std::size_t k = 0; k < count; ++k)
    indices[k] = static_cast<std::int32_t>(from[k] & 0xffffffffu);
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

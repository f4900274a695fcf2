#pragma once
// Putting a level's selected candidates in raster order (y, then x), the order descriptors are
// computed and keypoints written in. One selection sorts; a level selected at many thresholds
// (the sweep) ranks its candidates once and sets a bit per place instead.
#include <cstdint>
#include <vector>

#include "core/distribution/candidate.hpp"

namespace aief {

// The candidates in raster order and each one's place in it, built by the first sort after
// detection (clear() when the candidates change), with the buffers of that sort and of
// sort_in_raster_order.
struct RasterRanks {
  std::vector<std::int32_t> order, rank;
  std::vector<std::int32_t> counting_starts;  // counting sort's bucket starts
  std::vector<std::uint64_t> place_bits;      // a bit per place of the indices being sorted
  std::vector<std::uint64_t> radix_keys;      // sort_in_raster_order: (y * width + x, index) twice

  void clear() { rank.clear(); }
};

// Sorts candidate indices by raster_before, on a level `width` pixels wide (x < width, and
// width * height <= 2^32): a radix sort of the place y * width + x, a byte a pass (three on a
// 800 x 640 level), no compare to mispredict. `ranks` lends its radix_keys.
void sort_in_raster_order(const std::vector<Candidate>& candidates, int width,
                          std::vector<std::int32_t>& indices, RasterRanks& ranks);

// The same order as sort_in_raster_order, through the ranks: linear in the candidates. `width`,
// `height`: the level's size (the counting sort's key ranges).
void sort_by_raster_rank(const std::vector<Candidate>& candidates, int width, int height,
                         RasterRanks& ranks, std::vector<std::int32_t>& indices);

}  // namespace aief

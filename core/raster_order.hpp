#pragma once
// Putting a level's selected candidates in raster order (y, then x), the order descriptors are
// computed and keypoints written in. One selection sorts; a level selected at many thresholds
// (the sweep) ranks its candidates once and sets a bit per place instead.
#include <cstdint>
#include <vector>

#include "core/candidate.hpp"

namespace aief {

// Sorts candidate indices by raster_before.
void sort_in_raster_order(const std::vector<Candidate>& candidates,
                          std::vector<std::int32_t>& indices);

// The candidates in raster order and each one's place in it, built by the first sort after
// detection (clear() when the candidates change), with the buffers of that sort.
struct RasterRanks {
  std::vector<std::int32_t> order, rank;
  std::vector<std::int32_t> counting_starts;  // counting sort's bucket starts
  std::vector<std::uint64_t> place_bits;      // a bit per place of the indices being sorted

  void clear() { rank.clear(); }
};

// The same order as sort_in_raster_order, through the ranks: linear in the candidates. `width`,
// `height`: the level's size (the counting sort's key ranges).
void sort_by_raster_rank(const std::vector<Candidate>& candidates, int width, int height,
                         RasterRanks& ranks, std::vector<std::int32_t>& indices);

}  // namespace aief

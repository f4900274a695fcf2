#include "core/detection/scale_selection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace aief {

void index_candidates(const std::vector<Candidate>& candidates, int width, int height,
                      ScaleIndex& index) {
  index.width = width;
  index.height = height;
  index.cols = (width + kScaleBucket - 1) / kScaleBucket;
  index.rows = (height + kScaleBucket - 1) / kScaleBucket;
  const std::size_t buckets =
      static_cast<std::size_t>(index.cols) * static_cast<std::size_t>(index.rows);
  index.starts.assign(buckets + 1, 0);
  const auto bucket_of = [&](const Candidate& c) {
    return static_cast<std::size_t>(c.y / kScaleBucket) * static_cast<std::size_t>(index.cols) +
           static_cast<std::size_t>(c.x / kScaleBucket);
  };
  for (const Candidate& c : candidates) ++index.starts[bucket_of(c) + 1];
  for (std::size_t b = 1; b <= buckets; ++b) index.starts[b] += index.starts[b - 1];
  index.order.resize(candidates.size());
  std::vector<std::int32_t> next(index.starts.begin(), index.starts.end() - 1);
  for (std::size_t i = 0; i < candidates.size(); ++i)
    index.order[static_cast<std::size_t>(next[bucket_of(candidates[i])]++)] =
        static_cast<std::int32_t>(i);
}

namespace {

// Whether a candidate of `other` near `c` (of `here`) beats it. `other_is_finer` breaks ties.
bool beaten(const Candidate& c, int strength, const ScaleIndex& here, const ScaleLevel& other,
            bool other_is_finer) {
  const ScaleIndex& index = *other.index;
  const std::vector<Candidate>& candidates = *other.candidates;
  // Exact test, per axis: |(2 x_o + 1) W_here - (2 x_c + 1) W_other| <= 2 K W_fine.
  const std::int64_t wh = here.width, hh = here.height, wo = index.width, ho = index.height;
  const std::int64_t w_fine = std::max(wh, wo), h_fine = std::max(hh, ho);
  const std::int64_t cx = (2 * std::int64_t{c.x} + 1) * wo, cy = (2 * std::int64_t{c.y} + 1) * ho;
  const std::int64_t tx = 2 * kScaleWindow * w_fine, ty = 2 * kScaleWindow * h_fine;
  // The buckets to look in, from the same bound with two pixels to spare.
  const double ux = static_cast<double>(cx) / static_cast<double>(2 * wh) - 0.5;
  const double uy = static_cast<double>(cy) / static_cast<double>(2 * hh) - 0.5;
  const double rx = static_cast<double>(tx) / static_cast<double>(2 * wh) + 2;
  const double ry = static_cast<double>(ty) / static_cast<double>(2 * hh) + 2;
  const int bx0 = std::max(0, static_cast<int>(std::floor(ux - rx)) / kScaleBucket);
  const int by0 = std::max(0, static_cast<int>(std::floor(uy - ry)) / kScaleBucket);
  const int bx1 = std::min(index.cols - 1, static_cast<int>(std::floor(ux + rx)) / kScaleBucket);
  const int by1 = std::min(index.rows - 1, static_cast<int>(std::floor(uy + ry)) / kScaleBucket);
  for (int by = by0; by <= by1; ++by)
    for (int bx = bx0; bx <= bx1; ++bx) {
      const std::size_t b = static_cast<std::size_t>(by) * static_cast<std::size_t>(index.cols) +
                            static_cast<std::size_t>(bx);
      for (std::int32_t k = index.starts[b]; k < index.starts[b + 1]; ++k) {
        const Candidate& o =
            candidates[static_cast<std::size_t>(index.order[static_cast<std::size_t>(k)])];
        const int s = rank_strength(o);
        if (s < strength || (s == strength && !other_is_finer)) continue;
        if (std::llabs((2 * std::int64_t{o.x} + 1) * wh - cx) <= tx &&
            std::llabs((2 * std::int64_t{o.y} + 1) * hh - cy) <= ty)
          return true;
      }
    }
  return false;
}

}  // namespace

void mark_scale_extrema(const ScaleLevel& here, const ScaleLevel& finer, const ScaleLevel& coarser,
                        std::vector<std::uint8_t>& keep) {
  const std::vector<Candidate>& candidates = *here.candidates;
  keep.assign(candidates.size(), 1);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& c = candidates[i];
    const int strength = rank_strength(c);
    if ((finer.candidates && beaten(c, strength, *here.index, finer, true)) ||
        (coarser.candidates && beaten(c, strength, *here.index, coarser, false)))
      keep[i] = 0;
  }
}

void remove_unkept_candidates(const std::vector<std::uint8_t>& keep, LevelBlocks& blocks) {
  std::vector<Candidate>& candidates = blocks.candidates;
  // removed_before[i]: candidates removed among [0, i).
  std::vector<std::int32_t> removed_before(candidates.size() + 1, 0);
  std::size_t out = 0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    removed_before[i + 1] = removed_before[i] + (keep[i] ? 0 : 1);
    if (keep[i]) candidates[out++] = candidates[i];
  }
  candidates.resize(out);
  for (BlockRange& range : blocks.candidate_range) {
    range.begin -= removed_before[static_cast<std::size_t>(range.begin)];
    range.end -= removed_before[static_cast<std::size_t>(range.end)];
  }
}

}  // namespace aief

#include "core/frame/level_selection.hpp"

#include "core/distribution/octree_orbslam.hpp"
#include "core/distribution/quadtree_weighted.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

void select_candidates(const PyramidLevel& level, const LevelBlocks& blocks, BlockMask mask,
                       const ExtractorOptions& options, int budget, SelectionScratch& scratch,
                       std::vector<std::int32_t>& selected) {
  const BlockGrid& grid = level.geometry.grid;
  selected.clear();
  if (options.distribution == Distribution::proportional) {
    std::vector<BlockRange>& kept = scratch.kept_blocks;
    kept.clear();
    std::int64_t total = 0;
    for (int b = 0; b < grid.count(); ++b)
      if (mask.kept(b)) {
        kept.push_back(blocks.candidate_range[static_cast<std::size_t>(b)]);
        total += kept.back().size();
      }
    const std::int64_t pool_size = candidate_pool_size(options.candidate_pool, budget);
    if (pool_size < 0 || total <= pool_size) {
      distribute_proportional(blocks.candidates, kept, budget, selected, scratch.distribution);
    } else {
      // The level's strongest candidates first (core/distribution/candidate_pool.hpp), then the
      // same water level.
      pool_candidates(blocks.candidates, kept, pool_size, scratch.pooled, scratch.pooled_index,
                      scratch.pooled_blocks, scratch.pool);
      distribute_proportional(scratch.pooled, scratch.pooled_blocks, budget, selected,
                              scratch.distribution);
      for (std::int32_t& index : selected)
        index = scratch.pooled_index[static_cast<std::size_t>(index)];
    }
  } else {
    // The quadtree sees the kept blocks' candidates as one set, over ORB-SLAM2's rectangle.
    std::vector<Candidate>& set = scratch.quadtree_set;
    std::vector<std::int32_t>& set_index = scratch.quadtree_index;
    set.clear();
    set_index.clear();
    if (options.detection_cells == DetectionCells::orbslam) {
      // ORB-SLAM's order (its octree's tie-breaks read it), the kept blocks' candidates only.
      for (std::int32_t i : blocks.orbslam_order) {
        const Candidate& c = blocks.candidates[static_cast<std::size_t>(i)];
        if (!mask.kept(block_of(grid, c.x, c.y))) continue;
        set.push_back(c);
        set_index.push_back(i);
      }
    } else {
      for (int b = 0; b < grid.count(); ++b) {
        if (!mask.kept(b)) continue;
        const BlockRange range = blocks.candidate_range[static_cast<std::size_t>(b)];
        for (std::int32_t i = range.begin; i < range.end; ++i) {
          set.push_back(blocks.candidates[static_cast<std::size_t>(i)]);
          set_index.push_back(i);
        }
      }
    }
    constexpr int kQuadtreeMargin = kEdgeBorder - 3;  // ORB-SLAM2's minBorderX
    if (options.quadtree_weight == QuadtreeWeight::entropy) {
      // The entropy-weighted quadtree: each candidate weighs its block's entropy (computed for this
      // option when the mask is off, core/frame/frame_analysis.cpp). It replaces either tie rule.
      std::vector<std::int64_t>& weights = scratch.quadtree_weights;
      weights.resize(set.size());
      for (std::size_t i = 0; i < set.size(); ++i)
        weights[i] = entropy_weight(
            blocks.entropy_bits[static_cast<std::size_t>(block_of(grid, set[i].x, set[i].y))]);
      distribute_quadtree_weighted(set, weights, kQuadtreeMargin,
                                   level.geometry.width - kQuadtreeMargin, kQuadtreeMargin,
                                   level.geometry.height - kQuadtreeMargin, budget, selected);
    } else if (options.quadtree_ties == QuadtreeTies::orbslam)
      distribute_octree_orbslam(set, kQuadtreeMargin, level.geometry.width - kQuadtreeMargin,
                                kQuadtreeMargin, level.geometry.height - kQuadtreeMargin, budget,
                                selected);
    else
      distribute_quadtree(set, kQuadtreeMargin, level.geometry.width - kQuadtreeMargin,
                          kQuadtreeMargin, level.geometry.height - kQuadtreeMargin, budget,
                          selected, scratch.distribution);
    for (std::int32_t& index : selected) index = set_index[static_cast<std::size_t>(index)];
  }
}

}  // namespace aief

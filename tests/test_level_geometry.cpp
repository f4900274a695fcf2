// Block grids (core/level/level_geometry.hpp): block_of's arithmetic equals the definition, the
// number of inner edges at or before the pixel, for every pixel of many level sizes and block
// sizes, the pixels around the grid's area included (they take the nearest block).
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "core/level/level_geometry.hpp"

namespace aief {
namespace {

int inner_edges_at_or_before(const std::vector<int>& edges, int v) {
  return static_cast<int>(std::upper_bound(edges.begin() + 1, edges.end() - 1, v) -
                          (edges.begin() + 1));
}

TEST(BlockGrid, BlockOfCountsTheInnerEdgesAtOrBeforeThePixel) {
  for (const int block_size : {8, 17, 32, 35, 64})
    for (int width = 39; width < 400; width += 23)
      for (int height = 39; height < 300; height += 37) {
        const BlockGrid grid = make_block_grid(width, height, block_size);
        ASSERT_GT(grid.count(), 0);
        for (int y = 0; y < height; ++y)
          for (int x = 0; x < width; ++x) {
            const int expected = inner_edges_at_or_before(grid.row_edges, y) * grid.cols() +
                                 inner_edges_at_or_before(grid.col_edges, x);
            ASSERT_EQ(block_of(grid, x, y), expected)
                << width << "x" << height << ", blocks of " << block_size << ", at (" << x << ", "
                << y << ")";
          }
      }
}

}  // namespace
}  // namespace aief

#pragma once
// Sizes, scales, feature budgets and block grids of the pyramid levels (docs/design.md §2, §3,
// §6).
// Depends only on the image size and the options, so an extractor computes it once per size.
#include <vector>

#include "aief/options.hpp"

namespace aief {

// Blocks tile the area where a keypoint may lie, [kEdgeBorder, size - kEdgeBorder) on each axis.
// Column c spans x in [col_edges[c], col_edges[c + 1]); a short last column (or row) narrower
// than half a block is merged into its neighbour, so no block is tiny.
struct BlockGrid {
  std::vector<int> col_edges;  // cols + 1 entries
  std::vector<int> row_edges;  // rows + 1 entries
  // An empty grid (a level too small for keypoints) has no edges at all: 0 columns, 0 rows.
  int cols() const { return col_edges.empty() ? 0 : static_cast<int>(col_edges.size()) - 1; }
  int rows() const { return row_edges.empty() ? 0 : static_cast<int>(row_edges.size()) - 1; }
  int count() const { return cols() * rows(); }
};

BlockGrid make_block_grid(int width, int height, int block_size);

// The block holding level pixel (x, y), which lies in the grid's area:
// block_row(grid, y) * grid.cols() + block_column(grid, x). Pixels outside the area take the
// nearest column or row. Arithmetic, not a search: the edges are begin + i * block_size but the
// last (make_block_grid), so the column is the number of inner edges at or left of x, that
// quotient clamped to [0, cols - 1].
inline int block_index_on_axis(const std::vector<int>& edges, int v) {
  const int count = static_cast<int>(edges.size()) - 1;
  if (count <= 1) return 0;
  const int index = (v - edges[0]) / (edges[1] - edges[0]);  // truncated: <= 0 left of edges[0]
  return index < 0 ? 0 : index > count - 1 ? count - 1 : index;
}
inline int block_column(const BlockGrid& grid, int x) {
  return block_index_on_axis(grid.col_edges, x);
}
inline int block_row(const BlockGrid& grid, int y) {
  return block_index_on_axis(grid.row_edges, y);
}
inline int block_of(const BlockGrid& grid, int x, int y) {
  return block_row(grid, y) * grid.cols() + block_column(grid, x);
}

struct LevelGeometry {
  int width = 0;
  int height = 0;
  float scale = 1;  // level-0 pixels per level pixel: scale_factor^n in float (ORB-SLAM2)
  int n_features =
      0;  // N_n of Eq. 12-17 over the usable levels, ORB-SLAM2's rounding, rest on the last
  BlockGrid grid;  // empty when the level is smaller than 2 * kEdgeBorder + 1
};

// All n_levels levels. Levels too small to hold a keypoint keep their size but have no blocks and
// no budget (their share goes to the usable levels), and are not built.
std::vector<LevelGeometry> level_geometry(int width, int height, const ExtractorOptions& options);

// A level can hold keypoints (and is built) when both sides are >= 2 * kEdgeBorder + 1.
inline bool level_is_usable(int width, int height) {
  return width >= 2 * kEdgeBorder + 1 && height >= 2 * kEdgeBorder + 1;
}

// The pixels of the levels built (the usable ones), summed; allocates nothing.
long long pyramid_pixels(int width, int height, const ExtractorOptions& options);

}  // namespace aief

#include "core/detection/score_band.hpp"

#include <algorithm>

namespace aief {

namespace {

// Narrowest run of FAST scores computed at once: two AVX-512 batches.
constexpr int kMinScoredRun = 128;

}  // namespace

void size_score_band(const LevelGeometry& geometry, GrayImage& band) {
  int tallest_block_row = 0;
  for (int r = 0; r < geometry.grid.rows(); ++r)
    tallest_block_row =
        std::max(tallest_block_row, geometry.grid.row_edges[static_cast<std::size_t>(r) + 1] -
                                        geometry.grid.row_edges[static_cast<std::size_t>(r)]);
  band.resize(geometry.width, tallest_block_row + 2);
}

void compute_score_rows(ImageView pixels, const KernelTable& kernels, int fast_min_threshold,
                        GrayImage& band, int top, int y_begin, int y_end, int x_begin, int x_end) {
  const int w = pixels.width, h = pixels.height;
  y_begin = std::max(y_begin, 3);
  y_end = std::min(y_end, h - 3);
  x_begin = std::max(x_begin, 3);
  x_end = std::min(x_end, w - 3);
  if (x_begin >= x_end) return;
  if (x_end - x_begin < kMinScoredRun) {
    x_end = std::min(w - 3, x_begin + kMinScoredRun);
    x_begin = std::max(3, x_end - kMinScoredRun);
  }
  const MutableImageView scores = band.mutable_view();
  for (int y = y_begin; y < y_end; ++y)
    kernels.fast9_scores_row(pixels.row(y), pixels.stride, x_begin, x_end, fast_min_threshold,
                             scores.row(y - top));
}

}  // namespace aief

#include "core/entropy/level_entropy.hpp"

#include <cstring>

#include "core/entropy/block_entropy.hpp"

namespace aief {

void compute_block_entropies(ImageView pixels, const BlockGrid& grid, EntropyMeasure measure,
                             const KernelTable& kernels, LevelBlocks& blocks,
                             std::uint32_t* whole) {
  blocks.entropy_bits.resize(static_cast<std::size_t>(grid.count()));
  blocks.uniform.resize(static_cast<std::size_t>(grid.count()));
  std::uint32_t hist[256];
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      const int x0 = grid.col_edges[static_cast<std::size_t>(c)],
                x1 = grid.col_edges[static_cast<std::size_t>(c) + 1];
      const int y0 = grid.row_edges[static_cast<std::size_t>(r)],
                y1 = grid.row_edges[static_cast<std::size_t>(r) + 1];
      std::memset(hist, 0, sizeof hist);
      kernels.accumulate_histogram(pixels.row(y0) + x0, pixels.stride, x1 - x0, y1 - y0, hist);
      const int area = (x1 - x0) * (y1 - y0);
      blocks.entropy_bits[static_cast<std::size_t>(r * grid.cols() + c)] =
          entropy_bits(hist, static_cast<std::uint64_t>(area), measure);
      blocks.uniform[static_cast<std::size_t>(r * grid.cols() + c)] =
          hist[pixels.row(y0)[x0]] == static_cast<std::uint32_t>(area) ? 1 : 0;
      if (whole != nullptr)
        for (int k = 0; k < 256; ++k) whole[k] += hist[k];
    }
  }
}

double whole_level_entropy_bits(ImageView pixels, EntropyMeasure measure,
                                const KernelTable& kernels, std::uint32_t whole[256]) {
  const int w = pixels.width, h = pixels.height, b = kEdgeBorder;
  kernels.accumulate_histogram(pixels.row(0), pixels.stride, w, b, whole);
  kernels.accumulate_histogram(pixels.row(h - b), pixels.stride, w, b, whole);
  kernels.accumulate_histogram(pixels.row(b), pixels.stride, b, h - 2 * b, whole);
  kernels.accumulate_histogram(pixels.row(b) + (w - b), pixels.stride, b, h - 2 * b, whole);
  return entropy_bits(whole, measure);
}

}  // namespace aief

#include "core/low_entropy_sharpen.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

#include "core/unsharp_mask.hpp"

namespace aief {

namespace {

constexpr std::int64_t kFullQ8 = 256 * kSharpenFullBits;

// Twice the centre of each span [edges[i], edges[i + 1]) in pixel indices: edges[i] + edges[i+1]
// - 1, so that pixel p sits at 2p and every position is an integer.
int doubled_centre(const std::vector<int>& edges, int i) {
  return edges[static_cast<std::size_t>(i)] + edges[static_cast<std::size_t>(i) + 1] - 1;
}

// The span below pixel p (the last whose centre is <= p, else 0) and the weight in 1/256 of the
// span after it: 0 before the first centre and from the last on.
void interpolation_of(const std::vector<int>& edges, int p, int& span, int& weight) {
  const int spans = static_cast<int>(edges.size()) - 1;
  int low = 0, high = spans - 1;  // binary search: the centres increase
  while (low < high) {
    const int middle = (low + high + 1) / 2;
    if (doubled_centre(edges, middle) <= 2 * p)
      low = middle;
    else
      high = middle - 1;
  }
  span = low;
  const int here = doubled_centre(edges, span);
  if (2 * p <= here || span + 1 == spans) {
    weight = 0;
    return;
  }
  const int length = doubled_centre(edges, span + 1) - here;
  weight = ((2 * p - here) * 256 + length / 2) / length;
}

}  // namespace

int sharpen_amount_q8(double entropy_bits) {
  const std::int64_t h = std::clamp<std::int64_t>(std::llround(entropy_bits * 256.0), 0, kFullQ8);
  return static_cast<int>(kUnsharpMaxAmountQ8 * (kFullQ8 - h) / kFullQ8);
}

void prepare_sharpen_columns(const BlockGrid& grid, int width, SharpenScratch& scratch) {
  scratch.column_block.resize(static_cast<std::size_t>(width));
  scratch.column_weight.resize(static_cast<std::size_t>(width));
  int span = 0, weight = 0;
  for (int x = 0; x < width; ++x) {
    interpolation_of(grid.col_edges, x, span, weight);
    scratch.column_block[static_cast<std::size_t>(x)] = span;
    scratch.column_weight[static_cast<std::size_t>(x)] = weight;
  }
  scratch.amount_row.resize(static_cast<std::size_t>(width));
  scratch.row_amounts.resize(static_cast<std::size_t>(grid.cols()));
}

void sharpen_amount_row(const BlockGrid& grid, int y, SharpenScratch& scratch) {
  const int cols = grid.cols();
  int r0 = 0, wy = 0;
  interpolation_of(grid.row_edges, y, r0, wy);
  const int r1 = std::min(r0 + 1, grid.rows() - 1);
  const int* above = scratch.block_amounts.data() + static_cast<std::ptrdiff_t>(r0) * cols;
  const int* below = scratch.block_amounts.data() + static_cast<std::ptrdiff_t>(r1) * cols;
  for (int c = 0; c < cols; ++c)
    scratch.row_amounts[static_cast<std::size_t>(c)] = above[c] * (256 - wy) + below[c] * wy;
  const std::size_t width = scratch.amount_row.size();
  for (std::size_t x = 0; x < width; ++x) {
    const int c0 = scratch.column_block[x], wx = scratch.column_weight[x];
    const int c1 = std::min(c0 + 1, cols - 1);
    // <= 512 * 256 * 256 = 2^25: fits, and is non-negative, so the shift rounds half up.
    const std::int32_t sum = scratch.row_amounts[static_cast<std::size_t>(c0)] * (256 - wx) +
                             scratch.row_amounts[static_cast<std::size_t>(c1)] * wx;
    scratch.amount_row[x] = static_cast<std::int16_t>((sum + (1 << 15)) >> 16);
  }
}

bool sharpen_low_entropy_blocks(ImageView pixels, const BlockGrid& grid,
                                const std::vector<double>& entropy_bits, const KernelTable& kernels,
                                SharpenScratch& scratch, GrayImage& out) {
  assert(grid.count() > 0 && entropy_bits.size() == static_cast<std::size_t>(grid.count()));
  (void)kernels;
  scratch.block_amounts.resize(entropy_bits.size());
  bool any = false;
  for (std::size_t b = 0; b < entropy_bits.size(); ++b) {
    scratch.block_amounts[b] = sharpen_amount_q8(entropy_bits[b]);
    any = any || scratch.block_amounts[b] != 0;
  }
  if (!any) return false;
  out.resize(pixels.width, pixels.height);
  const MutableImageView sharpened = out.mutable_view();
  prepare_sharpen_columns(grid, pixels.width, scratch);
  scratch.column_sums.resize(static_cast<std::size_t>(pixels.width) + 4);
  for (int y = 0; y < pixels.height; ++y) {
    sharpen_amount_row(grid, y, scratch);
    const bool row_sharpened = std::any_of(scratch.row_amounts.begin(), scratch.row_amounts.end(),
                                           [](std::int32_t amount) { return amount != 0; });
    if (!row_sharpened) {  // every amount 0: the kernel would copy the row
      std::memcpy(sharpened.row(y), pixels.row(y), static_cast<std::size_t>(pixels.width));
      continue;
    }
    unsharp_row_scalar(pixels, y, scratch.amount_row.data(), scratch.column_sums.data(),
                       sharpened.row(y));
  }
  return true;
}

}  // namespace aief

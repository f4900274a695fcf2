#include "core/entropy/low_entropy_sharpen.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

#include "core/kernels/unsharp_row.hpp"

namespace aief {

namespace {

constexpr std::int64_t kFullQ8 = 256 * kSharpenFullBits;
// Interpolation weights in 1/64: the horizontal step's products (amount difference <= 512 times
// a weight < 64) then fit 16-bit lanes, which even the baseline x86-64 vectorises.
constexpr int kWeightOne = 64;

// Twice the centre of each span [edges[i], edges[i + 1]) in pixel indices: edges[i] + edges[i+1]
// - 1, so that pixel p sits at 2p and every position is an integer.
int doubled_centre(const std::vector<int>& edges, int i) {
  return edges[static_cast<std::size_t>(i)] + edges[static_cast<std::size_t>(i) + 1] - 1;
}

// The span below pixel p (the last whose centre is <= p, else 0) and the weight of the span after
// it in 1/kWeightOne, rounded down (< kWeightOne): 0 before the first centre and from the last on.
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
  weight = (2 * p - here) * kWeightOne / (doubled_centre(edges, span + 1) - here);
}

}  // namespace

int sharpen_amount_q8(double entropy_bits) {
  const std::int64_t h = std::clamp<std::int64_t>(std::llround(entropy_bits * 256.0), 0, kFullQ8);
  return static_cast<int>(kUnsharpMaxAmountQ8 * (kFullQ8 - h) / kFullQ8);
}

void prepare_sharpen_columns(const BlockGrid& grid, int width, SharpenScratch& scratch) {
  const int cols = grid.cols();
  scratch.column_weight.resize(static_cast<std::size_t>(width));
  scratch.segment_begin.assign(static_cast<std::size_t>(cols) + 1, width);
  int span = 0, weight = 0;
  for (int x = width - 1; x >= 0; --x) {  // the spans do not decrease with x
    interpolation_of(grid.col_edges, x, span, weight);
    scratch.column_weight[static_cast<std::size_t>(x)] = static_cast<std::int16_t>(weight);
    scratch.segment_begin[static_cast<std::size_t>(span)] = x;
  }
  for (int c = cols - 1; c >= 0; --c)  // a span no pixel falls in is empty, not the rest
    scratch.segment_begin[static_cast<std::size_t>(c)] =
        std::min(scratch.segment_begin[static_cast<std::size_t>(c)],
                 scratch.segment_begin[static_cast<std::size_t>(c) + 1]);
  scratch.amount_row.resize(static_cast<std::size_t>(width));
  scratch.segment_start.resize(static_cast<std::size_t>(width));
  scratch.segment_slope.resize(static_cast<std::size_t>(width));
  scratch.row_amounts.resize(static_cast<std::size_t>(cols));
}

bool sharpen_block_column_amounts(const BlockGrid& grid, int y, SharpenScratch& scratch) {
  const int cols = grid.cols();
  int r0 = 0, wy = 0;
  interpolation_of(grid.row_edges, y, r0, wy);
  const int r1 = std::min(r0 + 1, grid.rows() - 1);
  const int* above = scratch.block_amounts.data() + static_cast<std::ptrdiff_t>(r0) * cols;
  const int* below = scratch.block_amounts.data() + static_cast<std::ptrdiff_t>(r1) * cols;
  bool any = false;
  for (int c = 0; c < cols; ++c) {
    const int amount = above[c] + (((below[c] - above[c]) * wy + kWeightOne / 2) >> 6);
    scratch.row_amounts[static_cast<std::size_t>(c)] = static_cast<std::int16_t>(amount);
    any = any || amount != 0;
  }
  return any;
}

void sharpen_amount_row(const BlockGrid& grid, SharpenScratch& scratch) {
  const int cols = grid.cols();
  const std::size_t width = scratch.amount_row.size();
  // Between two block centres: a0 + floor((a1 - a0) w / 64), |a1 - a0| w <= 512 * 63 < 2^15.
  // Each segment's a0 and a1 - a0 are spread over its pixels first, so the multiply-add is one
  // loop over the row, which the compiler vectorises in 16-bit lanes (a vector loop per segment
  // of a block's width costs more than it saves). >> is floor in C++20.
  std::int16_t* __restrict start = scratch.segment_start.data();
  std::int16_t* __restrict slope = scratch.segment_slope.data();
  for (int c = 0; c < cols; ++c) {
    const std::int16_t a0 = scratch.row_amounts[static_cast<std::size_t>(c)];
    const std::int16_t a1 =
        scratch.row_amounts[static_cast<std::size_t>(std::min(c + 1, cols - 1))];
    const int x_begin = scratch.segment_begin[static_cast<std::size_t>(c)];
    const int x_end = scratch.segment_begin[static_cast<std::size_t>(c) + 1];
    std::fill(start + x_begin, start + x_end, a0);
    std::fill(slope + x_begin, slope + x_end, static_cast<std::int16_t>(a1 - a0));
  }
  const std::int16_t* __restrict weights = scratch.column_weight.data();
  std::int16_t* __restrict amounts = scratch.amount_row.data();
  for (std::size_t x = 0; x < width; ++x)
    amounts[x] = static_cast<std::int16_t>(start[x] +
                                           (static_cast<std::int16_t>(slope[x] * weights[x]) >> 6));
}

bool sharpen_low_entropy_blocks(ImageView pixels, const BlockGrid& grid,
                                const std::vector<double>& entropy_bits, const KernelTable& kernels,
                                SharpenScratch& scratch, GrayImage& out) {
  assert(grid.count() > 0 && entropy_bits.size() == static_cast<std::size_t>(grid.count()));
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
    if (!sharpen_block_column_amounts(grid, y, scratch)) {  // all 0: the kernel would copy
      std::memcpy(sharpened.row(y), pixels.row(y), static_cast<std::size_t>(pixels.width));
      continue;
    }
    sharpen_amount_row(grid, scratch);
    kernels.unsharp_row(pixels, y, scratch.amount_row.data(), scratch.column_sums.data(),
                        sharpened.row(y));
  }
  return true;
}

}  // namespace aief

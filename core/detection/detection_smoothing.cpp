#include "core/detection/detection_smoothing.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>

namespace aief {

namespace {

// Output rows a band of the two-pass smoothing makes at a time (docs/speed.md, "The quality mode").
constexpr int kSmoothingBandRows = 32;

// Two passes without a whole first-pass image: the first pass's rows that a band of
// kSmoothingBandRows output rows reads (2 more above and below) are held in `between`,
// kSmoothingBandRows + 4 rows that stay in cache, and the second pass reads them through a view of
// those rows. Inside the image the view holds every row the 5x5 kernel reads; at the image's top
// and bottom its first and last rows are the image's, so the kernel's clamping replicates the same
// rows as on the whole image: the same bytes.
void smooth_twice_in_bands(ImageView pixels, const KernelTable& kernels, SmoothingScratch& scratch,
                           GrayImage& out) {
  const int width = pixels.width, height = pixels.height;
  scratch.between.resize(width, kSmoothingBandRows + 4);
  const MutableImageView held = scratch.between.mutable_view();
  const MutableImageView destination = out.mutable_view();
  std::uint16_t* sums = scratch.column_sums.data();
  int top = 0, end = 0;  // first-pass rows [top, end) are held at held rows [0, end - top)
  for (int y0 = 0; y0 < height; y0 += kSmoothingBandRows) {
    const int y1 = std::min(height, y0 + kSmoothingBandRows);
    const int need_top = std::max(0, y0 - 2), need_end = std::min(height, y1 + 2);
    if (need_top > top) {  // the rows still needed move up
      std::memmove(
          held.row(0), held.row(need_top - top),
          static_cast<std::size_t>(end - need_top) * static_cast<std::size_t>(held.stride));
      top = need_top;
    }
    for (int y = end; y < need_end; ++y) kernels.binomial5_row(pixels, y, sums, held.row(y - top));
    end = need_end;
    const ImageView band{held.data, width, end - top, held.stride};
    for (int y = y0; y < y1; ++y) kernels.binomial5_row(band, y - top, sums, destination.row(y));
  }
}

}  // namespace

void smooth_for_detection(ImageView pixels, int passes, const KernelTable& kernels,
                          SmoothingScratch& scratch, GrayImage& out) {
  assert(!pixels.empty() && passes >= 1);
  const int width = pixels.width, height = pixels.height;
  out.resize(width, height);
  scratch.column_sums.resize(static_cast<std::size_t>(width) + 4);
  if (passes == 2 && height > kSmoothingBandRows + 4) {
    smooth_twice_in_bands(pixels, kernels, scratch, out);
    return;
  }
  if (passes >= 2) scratch.between.resize(width, height);
  // The last pass writes `out`, the one before it `between`, alternately back to the first.
  ImageView source = pixels;
  for (int pass = 0; pass < passes; ++pass) {
    GrayImage& target = (passes - 1 - pass) % 2 == 0 ? out : scratch.between;
    MutableImageView destination = target.mutable_view();
    for (int y = 0; y < height; ++y)
      kernels.binomial5_row(source, y, scratch.column_sums.data(), destination.row(y));
    source = target.view();
  }
}

}  // namespace aief

#include "core/level/detection_smoothing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aief {

int detection_smoothing_passes(double sigma) {
  if (!(sigma > 0)) return 0;
  return std::max(1, static_cast<int>(std::lround(sigma * sigma)));
}

void smooth_for_detection(ImageView pixels, int passes, const KernelTable& kernels,
                          SmoothingScratch& scratch, GrayImage& out) {
  assert(!pixels.empty() && passes >= 1);
  const int width = pixels.width, height = pixels.height;
  out.resize(width, height);
  if (passes >= 2) scratch.between.resize(width, height);
  scratch.column_sums.resize(static_cast<std::size_t>(width) + 4);
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

#include "core/fast9_detect.hpp"

#include <algorithm>
#include <cstring>

namespace aief {

void fast9_detect(ImageView image, int threshold, const KernelTable& kernels, std::vector<std::uint8_t>& scores,
                  std::vector<std::int32_t>& xs, std::vector<FastCorner>& corners) {
  corners.clear();
  const int w = image.width, h = image.height;
  if (w < 7 || h < 7) return;
  // Scores on [3, w - 3) x [3, h - 3), zero around, as OpenCV's buffers.
  scores.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (int y = 3; y < h - 3; ++y)
    kernels.fast9_scores_row(image.row(y), image.stride, 3, w - 3, threshold,
                             scores.data() + static_cast<std::ptrdiff_t>(y) * w);
  xs.resize(static_cast<std::size_t>(w));
  for (int y = 3; y < h - 3; ++y) {
    const std::uint8_t* row = scores.data() + static_cast<std::ptrdiff_t>(y) * w;
    const int found = kernels.fast9_local_maxima_row(row - w, row, row + w, 3, w - 3, xs.data());
    for (int i = 0; i < found; ++i) corners.push_back({xs[static_cast<std::size_t>(i)], y, row[xs[static_cast<std::size_t>(i)]]});
  }
}

}  // namespace aief

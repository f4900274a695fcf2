#include "tests/fast9_whole_image.hpp"

#include <algorithm>
#include <bit>

namespace aief {

void fast9_whole_image(ImageView image, int threshold, const KernelTable& kernels,
                       std::vector<std::uint8_t>& scores, std::vector<std::uint64_t>& maxima_bits,
                       std::vector<FastCorner>& corners) {
  corners.clear();
  const int w = image.width, h = image.height;
  if (w < 7 || h < 7) return;
  // Scores on [3, w - 3) x [3, h - 3), zero around, as OpenCV's buffers.
  scores.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (int y = 3; y < h - 3; ++y)
    kernels.fast9_scores_row(image.row(y), image.stride, 3, w - 3, threshold,
                             scores.data() + static_cast<std::ptrdiff_t>(y) * w);
  const int words = fast9_maxima_words(w - 6);
  maxima_bits.resize(2 * static_cast<std::size_t>(words));
  std::uint64_t* maxima = maxima_bits.data();
  for (int y = 3; y < h - 3; ++y) {
    const std::uint8_t* row = scores.data() + static_cast<std::ptrdiff_t>(y) * w;
    kernels.fast9_local_maxima_bits(row - w, row, row + w, 3, w - 3, threshold, maxima,
                                    maxima + words);
    for (int k = 0; k < words; ++k)
      for (std::uint64_t bits = maxima[k]; bits != 0; bits &= bits - 1) {
        const int x = 3 + 64 * k + std::countr_zero(bits);
        corners.push_back({x, y, row[x]});
      }
  }
}

}  // namespace aief

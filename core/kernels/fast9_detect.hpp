#pragma once
// FAST-9 over a whole image with suppression: what cv::FAST(image, kps, threshold, true) returns,
// from the row kernels of a kernel table. The pipeline itself detects per block (frame_analysis);
// this whole-image form is the oracle-comparable one for tests, benchmarks and `aief validate`.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

struct FastCorner {
  std::int32_t x = 0;
  std::int32_t y = 0;
  std::int32_t score = 0;
};

// Corners in raster order. `scores` and `maxima_bits` are caller-kept buffers (resized as
// needed) so repeated calls allocate nothing. Images smaller than 7x7 have no corner.
void fast9_detect(ImageView image, int threshold, const KernelTable& kernels,
                  std::vector<std::uint8_t>& scores, std::vector<std::uint64_t>& maxima_bits,
                  std::vector<FastCorner>& corners);

}  // namespace aief

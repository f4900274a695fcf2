#pragma once
// A test and benchmark helper, not where FAST runs: FAST-9 over a whole image with suppression,
// what cv::FAST(image, kps, threshold, true) returns, from the row kernels of a kernel table.
// The pipeline detects per block (core/detection/level_detection.hpp); this whole-image form is
// the one an OpenCV oracle compares with (tests/test_fast9.cpp, bench/bench_kernels.cpp).
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
void fast9_whole_image(ImageView image, int threshold, const KernelTable& kernels,
                       std::vector<std::uint8_t>& scores, std::vector<std::uint64_t>& maxima_bits,
                       std::vector<FastCorner>& corners);

}  // namespace aief

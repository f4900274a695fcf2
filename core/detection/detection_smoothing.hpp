#pragma once
// Detection on a smoothed level (ExtractorOptions::detection_smoothing, docs/design.md §5,
// "detection on a smoothed level"): FAST reads a copy of each level blurred by passes of the 5x5
// binomial (core/kernels/binomial5_row.hpp, sigma 1 a pass), so a corner blurred in one image and
// sharp in the other is measured on alike pixels; orientation and descriptors read the level
// itself. A sigma s > 0 runs max(1, round(s^2)) passes (variances add: sigma sqrt(passes)), so
// 1 -> 1 pass, 1.5 -> 2 (sigma 1.41), 2 -> 4; the sigmas accepted, one per pass count, are
// core/options/detection_smoothing_values.hpp's. Integers throughout: the same bytes under every
// kernel set and thread count.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/options/detection_smoothing_values.hpp"

namespace aief {

// Reused buffers of one level's smoothing.
struct SmoothingScratch {
  std::vector<std::uint16_t> column_sums;  // the kernel's
  GrayImage between;                       // every other pass's output, with 2 passes or more
};

// `pixels` (not empty) blurred by `passes` (>= 1) passes into `out`, resized to the level.
void smooth_for_detection(ImageView pixels, int passes, const KernelTable& kernels,
                          SmoothingScratch& scratch, GrayImage& out);

}  // namespace aief

#pragma once
// A keypoint's orientation: the intensity centroid of its patch on the raw level (moments by
// KernelTable::ic_moments, core/kernels/ic_moments.hpp), as an angle in the formula
// ExtractorOptions::orientation names (docs/design.md §7). Detected keypoints and given ones
// (Extractor::describe) get theirs here alike.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

class KeypointAngles {
 public:
  // angles_deg[i] := the angle of points[i] on `level`, i in [0, count).
  void compute(const KernelTable& kernels, ImageView level, const PixelPoint* points, int count,
               Orientation orientation, float* angles_deg);

 private:
  std::vector<std::int32_t> m10_, m01_;
};

}  // namespace aief

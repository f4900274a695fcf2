#pragma once
// Intensity-centroid orientation over the disc of radius kPatchRadius (ORB-SLAM2's umax bound,
// docs/design.md §7): m10 = sum x I, m01 = sum y I as exact integers over the raw level.
#include <cstdint>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

// umax[v], v = 0..kPatchRadius: half width of the disc at row offset v (ORB-SLAM2's table).
const int* orientation_disc_umax();

// Moments of n keypoints; each point lies >= kPatchRadius from every edge of `level`.
void ic_moments_scalar(ImageView level, const PixelPoint* points, int n, std::int32_t* m10,
                       std::int32_t* m01);

// atan2(m01, m10) in degrees, in [0, 360). Shared by every kernel set.
float ic_angle_deg(std::int32_t m10, std::int32_t m01);

}  // namespace aief

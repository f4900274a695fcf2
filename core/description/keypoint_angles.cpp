#include "core/description/keypoint_angles.hpp"

#include "core/kernels/fast_atan2.hpp"
#include "core/kernels/ic_moments.hpp"

namespace aief {

void KeypointAngles::compute(const KernelTable& kernels, ImageView level, const PixelPoint* points,
                             int count, Orientation orientation, float* angles_deg) {
  m10_.resize(static_cast<std::size_t>(count));
  m01_.resize(static_cast<std::size_t>(count));
  kernels.ic_moments(level, points, count, m10_.data(), m01_.data());
  const auto angle = orientation == Orientation::opencv_fast ? orbslam_ic_angle_deg : ic_angle_deg;
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i)
    angles_deg[i] = angle(m10_[i], m01_[i]);
}

}  // namespace aief

#pragma once
// cv::fastAtan2 (OpenCV 4, core/src/mathfuncs_core: a 7th-order polynomial in float, about 0.01
// degrees from atan2), which ORB-SLAM2/3's IC_Angle takes of the moments (float)m01, (float)m10.
// The faithful mode's orientation (docs/design.md §7): with it a keypoint's angle, and so its
// rotated rBRIEF pattern, is ORB-SLAM's to the bit. Float operations in OpenCV's order, no
// contraction (the build's -ffp-contract=off), so one answer everywhere.
#include <cfloat>
#include <cmath>
#include <cstdint>

namespace aief {

inline float opencv_fast_atan2_deg(float y, float x) {
  constexpr float kDegrees = static_cast<float>(180 / 3.14159265358979323846);
  constexpr float p1 = 0.9997878412794807f * kDegrees, p3 = -0.3258083974640975f * kDegrees;
  constexpr float p5 = 0.1555786518463281f * kDegrees, p7 = -0.04432655554792128f * kDegrees;
  const float ax = std::abs(x), ay = std::abs(y);
  float a;
  if (ax >= ay) {
    const float c = ay / (ax + static_cast<float>(DBL_EPSILON)), c2 = c * c;
    a = (((p7 * c2 + p5) * c2 + p3) * c2 + p1) * c;
  } else {
    const float c = ax / (ay + static_cast<float>(DBL_EPSILON)), c2 = c * c;
    a = 90.f - (((p7 * c2 + p5) * c2 + p3) * c2 + p1) * c;
  }
  if (x < 0) a = 180.f - a;
  if (y < 0) a = 360.f - a;
  return a;
}

// ORB-SLAM's IC_Angle of the moments.
inline float orbslam_ic_angle_deg(std::int32_t m10, std::int32_t m01) {
  return opencv_fast_atan2_deg(static_cast<float>(m01), static_cast<float>(m10));
}

}  // namespace aief

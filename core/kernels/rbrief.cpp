#include "core/kernels/rbrief.hpp"

#include <cmath>

namespace aief {

namespace {

const std::int8_t kPattern[256][4] = {
#include "orb_pattern_31.inc"
};

}  // namespace

const std::int8_t (*orb_pattern_31())[4] { return kPattern; }

void rbrief_describe_scalar(ImageView blurred, const PixelPoint* points, const float* angle_deg,
                            int n, std::uint8_t* descriptors) {
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  const std::ptrdiff_t step = blurred.stride;
  for (int i = 0; i < n; ++i) {
    const float angle = angle_deg[i] * kRadiansPerDegree;
    const float a = static_cast<float>(std::cos(angle)), b = static_cast<float>(std::sin(angle));
    const std::uint8_t* center = blurred.row(points[i].y) + points[i].x;
    const auto sample = [&](int px, int py) {
      const float fx = static_cast<float>(px), fy = static_cast<float>(py);
      const long dx = std::lrint(fx * a - fy * b);
      const long dy = std::lrint(fx * b + fy * a);
      return center[dy * step + dx];
    };
    std::uint8_t* out = descriptors + static_cast<std::ptrdiff_t>(i) * 32;
    for (int byte = 0; byte < 32; ++byte) {
      int bits = 0;
      for (int bit = 0; bit < 8; ++bit) {
        const std::int8_t* pair = kPattern[byte * 8 + bit];
        bits |= (sample(pair[0], pair[1]) < sample(pair[2], pair[3]) ? 1 : 0) << bit;
      }
      out[byte] = static_cast<std::uint8_t>(bits);
    }
  }
}

}  // namespace aief

#include "core/kernels/rbrief_describe.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

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

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_rbrief_describe(const KernelTable& scalar, const KernelTable& other,
                                  const GrayImage& src) {
  const std::vector<PixelPoint> points = inner_points(src, kEdgeBorder, 5);
  if (points.empty()) return "";
  std::vector<float> angles(points.size());
  for (std::size_t i = 0; i < angles.size(); ++i)
    angles[i] = static_cast<float>((i * 37) % 360) + 0.25f * static_cast<float>(i % 4);
  std::vector<std::uint8_t> a(points.size() * 32), b(a.size());
  scalar.rbrief_describe(src.view(), points.data(), angles.data(), static_cast<int>(points.size()),
                         a.data());
  other.rbrief_describe(src.view(), points.data(), angles.data(), static_cast<int>(points.size()),
                        b.data());
  const std::string diff = first_difference(a, b, other.name, "descriptor byte");
  return diff.empty() ? "" : where(src, diff);
}

// The sample keypoints of blurred level 0.
KernelWorkload workload_rbrief_describe(const KernelBenchInputs& in, const KernelTable& k) {
  return {[&in, &k, descriptors = std::vector<std::uint8_t>(in.descriptors.size())]() mutable {
            k.rbrief_describe(in.blurred[0].view(), in.points.data(), in.angles_deg.data(),
                              static_cast<int>(in.points.size()), descriptors.data());
          },
          static_cast<long long>(in.points.size())};
}

}  // namespace aief

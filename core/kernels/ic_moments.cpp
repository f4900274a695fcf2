#include "core/kernels/ic_moments.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

namespace {

// ORB-SLAM2's umax: the disc's half width per row, made symmetric about the diagonal.
struct DiscTable {
  int umax[kPatchRadius + 2];
  DiscTable() {
    const int vmax = static_cast<int>(std::floor(kPatchRadius * std::sqrt(2.0) / 2 + 1));
    const int vmin = static_cast<int>(std::ceil(kPatchRadius * std::sqrt(2.0) / 2));
    const double r2 = static_cast<double>(kPatchRadius) * kPatchRadius;
    for (int v = 0; v <= vmax; ++v) umax[v] = static_cast<int>(std::lround(std::sqrt(r2 - v * v)));
    for (int v = kPatchRadius, v0 = 0; v >= vmin; --v) {
      while (umax[v0] == umax[v0 + 1]) ++v0;
      umax[v] = v0;
      ++v0;
    }
  }
};

const DiscTable kDisc;

}  // namespace

const int* orientation_disc_umax() { return kDisc.umax; }

void ic_moments_scalar(ImageView level, const PixelPoint* points, int n, std::int32_t* m10,
                       std::int32_t* m01) {
  const int* umax = kDisc.umax;
  const std::ptrdiff_t step = level.stride;
  for (int i = 0; i < n; ++i) {
    const std::uint8_t* center = level.row(points[i].y) + points[i].x;
    std::int32_t sum_x = 0, sum_y = 0;
    for (int u = -kPatchRadius; u <= kPatchRadius; ++u) sum_x += u * center[u];
    for (int v = 1; v <= kPatchRadius; ++v) {
      // Rows +v and -v together: x weights add, y weights subtract.
      std::int32_t v_sum = 0;
      const int d = umax[v];
      for (int u = -d; u <= d; ++u) {
        const int below = center[u + v * step], above = center[u - v * step];
        v_sum += below - above;
        sum_x += u * (below + above);
      }
      sum_y += v * v_sum;
    }
    m10[i] = sum_x;
    m01[i] = sum_y;
  }
}

float ic_angle_deg(std::int32_t m10, std::int32_t m01) {
  constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;
  double angle = std::atan2(static_cast<double>(m01), static_cast<double>(m10)) * kDegreesPerRadian;
  if (angle < 0) angle += 360.0;
  float result = static_cast<float>(angle);
  if (result >= 360.0f) result = 0.0f;
  return result;
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_ic_moments(const KernelTable& scalar, const KernelTable& other,
                             const GrayImage& src) {
  const std::vector<PixelPoint> points = inner_points(src, kPatchRadius, 3);
  if (points.empty()) return "";
  const int n = static_cast<int>(points.size());
  std::vector<std::int32_t> a10(points.size()), a01(points.size()), b10(points.size()),
      b01(points.size());
  scalar.ic_moments(src.view(), points.data(), n, a10.data(), a01.data());
  other.ic_moments(src.view(), points.data(), n, b10.data(), b01.data());
  std::string diff = first_difference(a10, b10, other.name, "m10 of point");
  if (diff.empty()) diff = first_difference(a01, b01, other.name, "m01 of point");
  return diff.empty() ? "" : where(src, diff);
}

// The sample keypoints of level 0.
KernelWorkload workload_ic_moments(const KernelBenchInputs& in, const KernelTable& k) {
  return {[&in, &k, m10 = std::vector<std::int32_t>(in.points.size()),
           m01 = std::vector<std::int32_t>(in.points.size())]() mutable {
            k.ic_moments(in.levels[0].view(), in.points.data(), static_cast<int>(in.points.size()),
                         m10.data(), m01.data());
          },
          static_cast<long long>(in.points.size())};
}

}  // namespace aief

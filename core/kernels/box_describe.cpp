#include "core/kernels/box_describe.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

namespace {

const BoxTest kTable[kBoxTests] = {
#include "box_table.inc"
};

const char* const kTableName =
#include "box_table.inc.name"
    ;

// A box's sum and area, clipped to the image (box_describe.hpp).
struct BoxSum {
  std::int64_t sum, area;
};

BoxSum box_sum(IntegralView integral, long cx, long cy, long r) {
  const long w = integral.width, h = integral.height;
  const long x0 = std::clamp(cx - r, 0L, w - 1), x1 = std::clamp(cx + r + 1, 1L, w);
  const long y0 = std::clamp(cy - r, 0L, h - 1), y1 = std::clamp(cy + r + 1, 1L, h);
  const std::uint32_t* top = integral.row(static_cast<int>(y0));
  const std::uint32_t* bottom = integral.row(static_cast<int>(y1));
  const std::uint32_t sum = bottom[x1] - bottom[x0] - top[x1] + top[x0];  // modulo 2^32
  return {static_cast<std::int64_t>(sum), static_cast<std::int64_t>((x1 - x0) * (y1 - y0))};
}

}  // namespace

const BoxTest* box_table() { return kTable; }
const char* box_table_name() { return kTableName; }

// A box centre lies at lrint(y + d), |d| <= scale * |(px, py)| up to float rounding, so within
// floor(scale * |(px, py)|) + 1 of y; its entries run from R above it to R + 1 below.
int box_reach(float scale) {
  long reach = 0;
  for (const BoxTest& test : kTable) {
    const long r = std::lrint(scale * static_cast<float>(test.radius));
    for (const auto& [px, py] : {std::pair{test.x1, test.y1}, std::pair{test.x2, test.y2}}) {
      const double distance = scale * std::hypot(static_cast<double>(px), static_cast<double>(py));
      reach = std::max(reach, static_cast<long>(std::floor(distance)) + 1 + r + 1);
    }
  }
  return static_cast<int>(reach);
}

void box_describe_scalar(IntegralView integral, const BoxPoint* points, const float* angle_deg,
                         int n, float scale, std::uint8_t* descriptors) {
  assert(integral.width >= 1 && integral.height >= 1 && scale > 0 && scale <= 4);
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  long radius[kBoxTests];
  for (int t = 0; t < kBoxTests; ++t)
    radius[t] = std::lrint(scale * static_cast<float>(kTable[t].radius));
  for (int k = 0; k < n; ++k) {
    const float angle = angle_deg[k] * kRadiansPerDegree;
    const float a = scale * static_cast<float>(std::cos(angle));
    const float b = scale * static_cast<float>(std::sin(angle));
    const float x = points[k].x, y = points[k].y;
    const auto box = [&](int px, int py, long r) {
      const float fx = static_cast<float>(px), fy = static_cast<float>(py);
      return box_sum(integral, std::lrint(x + (fx * a - fy * b)), std::lrint(y + (fx * b + fy * a)),
                     r);
    };
    std::uint8_t* out = descriptors + static_cast<std::ptrdiff_t>(k) * 32;
    std::memset(out, 0, 32);
    for (int t = 0; t < kBoxTests; ++t) {
      const BoxTest& test = kTable[t];
      const BoxSum one = box(test.x1, test.y1, radius[t]);
      const BoxSum two = box(test.x2, test.y2, radius[t]);
      const bool bit = 100 * one.sum * two.area - 100 * two.sum * one.area <=
                       test.threshold_hundredths * one.area * two.area;
      out[t / 8] = static_cast<std::uint8_t>(out[t / 8] | (bit ? 1 : 0) << (t % 8));
    }
  }
}

// Points everywhere: inside (the vector path), near and past the edges (clipped boxes: the
// reference), at fractional positions, at the level's scale and at a coarse level's on level 0.
std::string check_box_describe(const KernelTable& scalar, const KernelTable& other,
                               const GrayImage& src) {
  std::vector<BoxPoint> points;
  for (int y = -3; y < src.height() + 3; y += 4)
    for (int x = -2; x < src.width() + 2; x += 3)
      points.push_back({static_cast<float>(x) + 0.25f * static_cast<float>((x + y) % 3),
                        static_cast<float>(y) + 0.5f * static_cast<float>(x % 2)});
  if (points.empty()) return "";
  std::vector<float> angles(points.size());
  for (std::size_t i = 0; i < angles.size(); ++i)
    angles[i] = static_cast<float>((i * 37) % 360) + 0.25f * static_cast<float>(i % 4);
  IntegralImage integral;
  integral.compute(src.view());
  const int n = static_cast<int>(points.size());
  for (float scale : {kBoxLevelScale, 2.8f}) {
    std::vector<std::uint8_t> a(points.size() * 32), b(a.size());
    scalar.box_describe(integral.view(), points.data(), angles.data(), n, scale, a.data());
    other.box_describe(integral.view(), points.data(), angles.data(), n, scale, b.data());
    const std::string diff = first_difference(a, b, other.name, "descriptor byte");
    if (!diff.empty()) return where(src, "scale " + std::to_string(scale) + " " + diff);
  }
  return "";
}

// The sample keypoints of level 0 (rbrief_describe's), on level 0's integral image at the
// level's scale; the integral image is made once, outside the pass.
KernelWorkload workload_box_describe(const KernelBenchInputs& in, const KernelTable& k) {
  auto integral = std::make_shared<IntegralImage>();
  integral->compute(in.levels[0].view());
  std::vector<BoxPoint> points;
  for (const PixelPoint& p : in.points)
    points.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
  return {[&in, &k, integral, points = std::move(points),
           descriptors = std::vector<std::uint8_t>(in.points.size() * 32)]() mutable {
            k.box_describe(integral->view(), points.data(), in.angles_deg.data(),
                           static_cast<int>(points.size()), kBoxLevelScale, descriptors.data());
          },
          static_cast<long long>(in.points.size())};
}

}  // namespace aief

#pragma once
// The box descriptor in two passes per keypoint (contract: core/kernels/box_describe.hpp):
//   1. the 512 box centres in float lanes with exactly the scalar contract's operations
//      (multiply, multiply, subtract or add, add the position, round half to even), so they are
//      the same integers; stored as the offset of each box's top-left integral entry, box 1 and
//      box 2 of test t side by side (simd/point_pair_pattern.hpp, as rbrief_describe's samples),
//      while the lanes keep the smallest and largest box edge;
//   2. when no box is clipped (edges inside the image), the 256 tests with plain loads: four
//      entries a box at offsets fixed for the call (the radius is), S1 - S2 against the test's
//      threshold in integers, floor(threshold * A / 100), fixed for the call too; the bit shifted
//      into the descriptor word, last test first. A keypoint with a clipped box takes the scalar
//      reference (a few per cent of them, near the level's edges).
// No hardware gathers, for rbrief_describe's reason (simd/rbrief_describe/portable.hpp): on Zen 4 a
// gather costs more than its scalar loads.
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/kernels/box_describe.hpp"
#include "simd/point_pair_pattern.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace box_describe_detail {

constexpr int kBoxes = 2 * kBoxTests;

// The table's box centres, test t's two boxes side by side.
inline const PointPairPattern<kBoxTests>& box_pattern() {
  static const auto pattern = point_pair_pattern<kBoxTests>([table = box_table()](int t) {
    return std::array<int, 4>{table[t].x1, table[t].y1, table[t].x2, table[t].y2};
  });
  return pattern;
}

// floor(a / b) for b > 0.
inline std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

}  // namespace box_describe_detail

template <class Arch>
void box_describe(IntegralView integral, const BoxPoint* points, const float* angle_deg, int n,
                  float scale, std::uint8_t* descriptors) {
  using F32 = xsimd::batch<float, Arch>;
  using I32 = xsimd::batch<std::int32_t, Arch>;
  constexpr int kLanes = static_cast<int>(F32::size);
  using box_describe_detail::kBoxes;
  const PointPairPattern<kBoxTests>& pattern = box_describe_detail::box_pattern();
  const BoxTest* table = box_table();
  const std::ptrdiff_t stride = integral.stride;
  // The call's radii (scale is fixed), each box's, and per test the offsets of the other three
  // corners from the top-left one and the integer threshold on S1 - S2.
  alignas(64) std::int32_t radius[kBoxes];
  alignas(64) std::int32_t offset[kBoxes];
  std::ptrdiff_t right[kBoxTests], below[kBoxTests];
  std::int32_t threshold[kBoxTests];
  for (int t = 0; t < kBoxTests; ++t) {
    const long r = std::lrint(scale * static_cast<float>(table[t].radius));
    const long side = 2 * r + 1;
    radius[first_point(t)] = radius[second_point(t)] = static_cast<std::int32_t>(r);
    right[t] = side;
    below[t] = side * stride;
    threshold[t] = static_cast<std::int32_t>(box_describe_detail::floor_div(
        std::int64_t{table[t].threshold_hundredths} * side * side, 100));
  }
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  const I32 step(static_cast<std::int32_t>(stride)), first_row(integral.first_row);
  const std::uint32_t* entries = integral.data;
  for (int k = 0; k < n; ++k) {
    std::uint8_t* out = descriptors + static_cast<std::ptrdiff_t>(k) * 32;
    const float x = points[k].x, y = points[k].y;
    // Far outside the image the lanes could overflow: the reference clips such points.
    if (!(x >= 0 && y >= 0 && x < static_cast<float>(integral.width) &&
          y < static_cast<float>(integral.height))) {
      box_describe_scalar(integral, points + k, angle_deg + k, 1, scale, out);
      continue;
    }
    const float angle = angle_deg[k] * kRadiansPerDegree;
    const F32 a(scale * static_cast<float>(std::cos(angle)));
    const F32 b(scale * static_cast<float>(std::sin(angle)));
    const F32 fx(x), fy(y);
    I32 low(INT_MAX), high(INT_MIN);  // the smallest x0, y0 and largest x1 - W, y1 - H
    const I32 width(integral.width), height(integral.height);
#pragma GCC unroll 4
    for (int i = 0; i < kBoxes; i += kLanes) {
      const F32 px = F32::load_aligned(pattern.x + i), py = F32::load_aligned(pattern.y + i);
      const I32 cx = xsimd::nearbyint_as_int(fx + (px * a - py * b));
      const I32 cy = xsimd::nearbyint_as_int(fy + (px * b + py * a));
      const I32 r = I32::load_aligned(radius + i);
      const I32 left = cx - r, top = cy - r;
      low = xsimd::min(low, xsimd::min(left, top));
      high = xsimd::max(high, xsimd::max(cx + r + 1 - width, cy + r + 1 - height));
      ((top - first_row) * step + left).store_aligned(offset + i);
    }
    alignas(64) std::int32_t lows[kLanes], highs[kLanes];
    low.store_aligned(lows);
    high.store_aligned(highs);
    if (*std::min_element(lows, lows + kLanes) < 0 ||
        *std::max_element(highs, highs + kLanes) > 0) {
      box_describe_scalar(integral, points + k, angle_deg + k, 1, scale, out);
      continue;
    }
    std::uint64_t words[4];
    for (int w = 0; w < 4; ++w) {
      std::uint64_t bits = 0;
#pragma GCC unroll 8
      for (int t = 64 * w + 63; t >= 64 * w; --t) {
        const std::uint32_t* one = entries + offset[first_point(t)];
        const std::uint32_t* two = entries + offset[second_point(t)];
        const std::ptrdiff_t dx = right[t], dy = below[t];
        const std::uint32_t sum_one = one[dy + dx] - one[dy] - one[dx] + one[0];  // modulo 2^32
        const std::uint32_t sum_two = two[dy + dx] - two[dy] - two[dx] + two[0];
        const std::int32_t difference = static_cast<std::int32_t>(sum_one - sum_two);
        bits = bits + bits + (difference <= threshold[t] ? 1u : 0u);
      }
      words[w] = bits;
    }
    std::memcpy(out, words, sizeof words);
  }
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// A table of tests on point pairs as the describe kernels read it
// (simd/rbrief_describe/portable.hpp: the learned rBRIEF pattern's samples,
// simd/box_describe/portable.hpp: the box descriptor's box centres): the points' x and y as two
// float arrays, test t's two points side by side, at first_point(t) and second_point(t). Side by
// side, a test's two offsets are two plain loads on x86-64 and one ldpsw on AArch64 (qemu,
// bench/kernel_instructions.py, rbrief_describe, 875 points: 3.52 M neon64 instructions with all
// first points before all second ones, 3.28 M side by side; the same on x86-64).
#include <array>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

constexpr int first_point(int t) { return 2 * t; }
constexpr int second_point(int t) { return 2 * t + 1; }

template <int kTests>
struct PointPairPattern {
  static constexpr int kPoints = 2 * kTests;
  alignas(64) float x[kPoints], y[kPoints];
};

// The pattern of kTests tests, test t's points (x1, y1) and (x2, y2) = points(t).
template <int kTests, class Points>
PointPairPattern<kTests> point_pair_pattern(Points points) {
  PointPairPattern<kTests> pattern{};
  for (int t = 0; t < kTests; ++t) {
    const std::array<int, 4> p = points(t);
    pattern.x[first_point(t)] = static_cast<float>(p[0]);
    pattern.y[first_point(t)] = static_cast<float>(p[1]);
    pattern.x[second_point(t)] = static_cast<float>(p[2]);
    pattern.y[second_point(t)] = static_cast<float>(p[3]);
  }
  return pattern;
}

AIEF_SIMD_NAMESPACE_END

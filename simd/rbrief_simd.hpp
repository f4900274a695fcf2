#pragma once
// rBRIEF-256, vectorised where the arithmetic is: the 512 rotated sample offsets of a keypoint
// are computed in float lanes with exactly the scalar contract's operations (multiply, multiply,
// subtract or add, round half to even), so they are the same integers; the 256 tests then read
// the blurred level through those offsets. Contract: core/rbrief.hpp.
#include <cmath>
#include <cstdint>

#include "core/rbrief.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

template <class Arch>
void rbrief_describe(ImageView blurred, const PixelPoint* points, const float* angle_deg, int n, std::uint8_t* descriptors) {
  using F32 = xsimd::batch<float, Arch>;
  using I32 = xsimd::batch<std::int32_t, Arch>;
  constexpr int kSamples = 512;  // 256 pairs, two points each, in pattern order p0 q0 p1 q1 ...
  alignas(64) float px[kSamples], py[kSamples];
  const std::int8_t (*pattern)[4] = orb_pattern_31();
  for (int i = 0; i < 256; ++i) {
    px[2 * i] = pattern[i][0];
    py[2 * i] = pattern[i][1];
    px[2 * i + 1] = pattern[i][2];
    py[2 * i + 1] = pattern[i][3];
  }
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  const I32 step(static_cast<std::int32_t>(blurred.stride));
  alignas(64) std::int32_t offset[kSamples];
  for (int k = 0; k < n; ++k) {
    const float angle = angle_deg[k] * kRadiansPerDegree;
    const F32 a(static_cast<float>(std::cos(angle))), b(static_cast<float>(std::sin(angle)));
    for (int i = 0; i < kSamples; i += static_cast<int>(F32::size)) {
      const F32 x = F32::load_aligned(px + i), y = F32::load_aligned(py + i);
      const I32 dx = xsimd::nearbyint_as_int(x * a - y * b);
      const I32 dy = xsimd::nearbyint_as_int(x * b + y * a);
      (dy * step + dx).store_aligned(offset + i);
    }
    const std::uint8_t* center = blurred.row(points[k].y) + points[k].x;
    std::uint8_t* out = descriptors + static_cast<std::ptrdiff_t>(k) * 32;
    for (int byte = 0; byte < 32; ++byte) {
      unsigned bits = 0;
      for (int bit = 0; bit < 8; ++bit) {
        const int i = 2 * (byte * 8 + bit);
        bits |= static_cast<unsigned>(center[offset[i]] < center[offset[i + 1]]) << bit;
      }
      out[byte] = static_cast<std::uint8_t>(bits);
    }
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

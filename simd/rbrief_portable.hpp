#pragma once
// rBRIEF-256 in two passes per keypoint (contract: core/rbrief.hpp):
//   1. the 512 rotated sample offsets, in float lanes with exactly the scalar contract's
//      operations (multiply, multiply, subtract or add, round half to even), so they are the
//      same integers; stored as unsigned byte offsets from the patch's top-left corner
//      (kPatchReach rows and columns up-left of the keypoint), p and q of a test side by side;
//   2. the 256 tests with plain loads: one 64-bit load gives a test's two offsets, two byte
//      loads its samples, and the compare's carry is shifted into the descriptor word (adc),
//      last test first, so test i lands on bit i % 64 of word i / 64 (little-endian: bit i % 8
//      of byte i / 8).
// No hardware gathers: on the project's EPYC (Zen 4) a 16-lane gather costs more than its 16
// scalar loads (three issue a cycle). Same-run Google Benchmark, 1000 keypoints (bench
// rbrief_describe): 16-lane gathers 257 us, this kernel 160 us (AVX-512 offsets), 182 us (AVX2).
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/rbrief.hpp"
#include "simd/simd_support.hpp"

#if !defined(__aarch64__)
#include <immintrin.h>
#endif

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

namespace rbrief_detail {

constexpr int kTests = 256;
constexpr int kSamples = 2 * kTests;
// Every rotated sample lies within 18 pixels of its keypoint in x and y (the pattern's largest
// radius is 18.4: Rbrief.RotatedSamplesStayInsideTheEdgeBorder), and keypoints lie >= kEdgeBorder
// = 19 from every edge, so the patch corner is inside the view and every offset is >= 0.
constexpr int kPatchReach = 18;

// The learned pattern's points as two float arrays in sample order p0 q0 p1 q1 ...
struct SamplePattern {
  alignas(64) float x[kSamples], y[kSamples];
};

inline const SamplePattern& sample_pattern() {
  static const SamplePattern interleaved = [] {
    SamplePattern s{};
    const std::int8_t(*pattern)[4] = orb_pattern_31();
    for (int i = 0; i < kTests; ++i) {
      s.x[2 * i] = pattern[i][0];
      s.y[2 * i] = pattern[i][1];
      s.x[2 * i + 1] = pattern[i][2];
      s.y[2 * i + 1] = pattern[i][3];
    }
    return s;
  }();
  return interleaved;
}

// 2 * bits + bit: one adc on x86-64, where the compare's carry feeds it directly.
inline std::uint64_t shift_in(std::uint64_t bits, unsigned char bit) {
#if defined(__aarch64__)
  return bits + bits + bit;
#else
  unsigned long long shifted;
  _addcarry_u64(bit, bits, bits, &shifted);
  return shifted;
#endif
}

}  // namespace rbrief_detail

template <class Arch>
void rbrief_describe(ImageView blurred, const PixelPoint* points, const float* angle_deg, int n,
                     std::uint8_t* descriptors) {
  using F32 = xsimd::batch<float, Arch>;
  using I32 = xsimd::batch<std::int32_t, Arch>;
  using rbrief_detail::kPatchReach;
  using rbrief_detail::kSamples;
  const rbrief_detail::SamplePattern& pattern = rbrief_detail::sample_pattern();
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  const std::ptrdiff_t stride = blurred.stride;
  const I32 step(static_cast<std::int32_t>(stride));
  const I32 corner(static_cast<std::int32_t>(kPatchReach * stride + kPatchReach));
  alignas(64) std::uint32_t offset[kSamples];
  for (int k = 0; k < n; ++k) {
    const float angle = angle_deg[k] * kRadiansPerDegree;
    const F32 a(static_cast<float>(std::cos(angle))), b(static_cast<float>(std::sin(angle)));
    for (int i = 0; i < kSamples; i += static_cast<int>(F32::size)) {
      const F32 x = F32::load_aligned(pattern.x + i), y = F32::load_aligned(pattern.y + i);
      const I32 dx = xsimd::nearbyint_as_int(x * a - y * b);
      const I32 dy = xsimd::nearbyint_as_int(x * b + y * a);
      (dy * step + dx + corner).store_aligned(reinterpret_cast<std::int32_t*>(offset) + i);
    }
    const std::uint8_t* patch =
        blurred.row(points[k].y - kPatchReach) + (points[k].x - kPatchReach);
    std::uint64_t words[4];
    for (int w = 0; w < 4; ++w) {
      std::uint64_t bits = 0;
#pragma GCC unroll 16
      for (int t = 64 * w + 63; t >= 64 * w; --t) {
        std::uint64_t pair;  // offsets of p (low half) and q (high half) of test t
        std::memcpy(&pair, offset + 2 * t, sizeof pair);
        bits = rbrief_detail::shift_in(bits,
                                       patch[static_cast<std::uint32_t>(pair)] < patch[pair >> 32]);
      }
      words[w] = bits;
    }
    std::memcpy(descriptors + static_cast<std::ptrdiff_t>(k) * 32, words, sizeof words);
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

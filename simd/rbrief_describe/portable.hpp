#pragma once
// rBRIEF-256 in two passes per keypoint (contract: core/kernels/rbrief_describe.hpp):
//   1. the 512 rotated sample offsets, in float lanes with exactly the scalar contract's
//      operations (multiply, multiply, subtract or add, round half to even), so they are the
//      same integers; stored as signed byte offsets from the keypoint (dy * stride + dx), laid
//      out as simd/point_pair_pattern.hpp says (a test's two samples side by side);
//   2. the 256 tests with plain loads: two 32-bit loads give a test's offsets, a byte load and a
//      compare against the other byte in memory its result, and the compare's carry is shifted
//      into the descriptor word (adc), last test first, so test i lands on bit i % 64 of word
//      i / 64 (little-endian: bit i % 8 of byte i / 8). Five instructions a test on x86-64.
// No hardware gathers: on the project's EPYC (Zen 4) a 16-lane gather costs more than its 16
// scalar loads (three issue a cycle). Same-run Google Benchmark, 1000 keypoints (bench
// rbrief_describe): 16-lane gathers 257 us, this kernel 160 us (AVX-512 offsets), 182 us (AVX2).
// Callgrind (AVX2, graf, 1000 keypoints): 3.00 M instructions with p and q offsets side by side
// in one 64-bit load (split by a move and a shift) and the carry through _addcarry_u64 (GCC 12
// stores its result to the stack after every test), 2.38 M this way.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/kernels/rbrief_describe.hpp"
#include "simd/point_pair_pattern.hpp"
#include "simd/simd_support.hpp"

#if !defined(__aarch64__)
#include <immintrin.h>
#endif

AIEF_SIMD_NAMESPACE_BEGIN

namespace rbrief_describe_detail {

constexpr int kTests = 256;
constexpr int kSamples = 2 * kTests;

// The learned pattern's samples, test t's two side by side.
inline const PointPairPattern<kTests>& sample_pattern() {
  static const auto pattern = point_pair_pattern<kTests>([samples = orb_pattern_31()](int t) {
    return std::array<int, 4>{samples[t][0], samples[t][1], samples[t][2], samples[t][3]};
  });
  return pattern;
}

// 2 * bits + (p < q): on x86-64 a compare of p against q in memory and an adc of its carry (the
// intrinsic _addcarry_u64 would do it, but GCC 12 then stores the sum after every test).
inline std::uint64_t shift_in_less(std::uint64_t bits, std::uint8_t p, const std::uint8_t& q) {
#if defined(__aarch64__)
  return bits + bits + (p < q ? 1u : 0u);
#else
  __asm__("cmpb %2, %1\n\tadcq %0, %0" : "+r"(bits) : "q"(p), "m"(q) : "cc");
  return bits;
#endif
}

}  // namespace rbrief_describe_detail

template <class Arch>
void rbrief_describe(ImageView blurred, const PixelPoint* points, const float* angle_deg, int n,
                     std::uint8_t* descriptors) {
  using F32 = xsimd::batch<float, Arch>;
  using I32 = xsimd::batch<std::int32_t, Arch>;
  using rbrief_describe_detail::kSamples;
  const PointPairPattern<rbrief_describe_detail::kTests>& pattern =
      rbrief_describe_detail::sample_pattern();
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  const std::ptrdiff_t stride = blurred.stride;
  const I32 step(static_cast<std::int32_t>(stride));
  alignas(64) std::int32_t offset[kSamples];
  for (int k = 0; k < n; ++k) {
    const float angle = angle_deg[k] * kRadiansPerDegree;
    const F32 a(static_cast<float>(std::cos(angle))), b(static_cast<float>(std::sin(angle)));
#pragma GCC unroll 4
    for (int i = 0; i < kSamples; i += static_cast<int>(F32::size)) {
      const F32 x = F32::load_aligned(pattern.x + i), y = F32::load_aligned(pattern.y + i);
      const I32 dx = xsimd::nearbyint_as_int(x * a - y * b);
      const I32 dy = xsimd::nearbyint_as_int(x * b + y * a);
      (dy * step + dx).store_aligned(offset + i);
    }
    // Every sample lies inside the view: core/kernels/rbrief_describe.hpp (kSampleReach <
    // kEdgeBorder).
    const std::uint8_t* center = blurred.row(points[k].y) + points[k].x;
    std::uint64_t words[4];
    for (int w = 0; w < 4; ++w) {
      std::uint64_t bits = 0;
#pragma GCC unroll 16
      for (int t = 64 * w + 63; t >= 64 * w; --t)
        bits = rbrief_describe_detail::shift_in_less(bits, center[offset[first_point(t)]],
                                                     center[offset[second_point(t)]]);
      words[w] = bits;
    }
    std::memcpy(descriptors + static_cast<std::ptrdiff_t>(k) * 32, words, sizeof words);
  }
}

AIEF_SIMD_NAMESPACE_END

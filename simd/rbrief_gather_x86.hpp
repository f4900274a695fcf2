#pragma once
// rBRIEF-256 with hardware gathers (AVX2: 8 tests a step, AVX-512: 16): the contract of
// core/rbrief.hpp, the same bytes. The pattern is held split into its p and q points, so a step
// rotates the p and q points of consecutive tests i .. i + L - 1 with the scalar contract's
// float operations (multiply, multiply, subtract or add; cvtps2dq rounds half to even, as
// lrint), gathers the two samples of each test, and the lane compare p < q is the descriptor's
// next L bits as they are packed (test i to bit i % 8 of byte i / 8, lane order = bit order).
//
// A gather reads a 32-bit word at each sample, its byte and the three after it (only the byte
// is used). That stays inside `blurred`: every sample lies within 18 pixels of its point (the
// pattern's largest radius is 18.4: Rbrief.RotatedSamplesStayInsideTheEdgeBorder), and points
// lie >= kEdgeBorder = 19 from every edge, so a sample's row has a row below it in the view.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include <immintrin.h>

#include "core/rbrief.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

namespace rbrief_detail {

// The learned pattern as four float arrays: test i compares point (px[i], py[i]) with (qx[i], qy[i]).
struct SplitPattern {
  alignas(64) float px[256], py[256], qx[256], qy[256];
};

inline const SplitPattern& split_pattern() {
  static const SplitPattern split = [] {
    SplitPattern s{};
    const std::int8_t (*pattern)[4] = orb_pattern_31();
    for (int i = 0; i < 256; ++i) {
      s.px[i] = pattern[i][0];
      s.py[i] = pattern[i][1];
      s.qx[i] = pattern[i][2];
      s.qy[i] = pattern[i][3];
    }
    return s;
  }();
  return split;
}

}  // namespace rbrief_detail

template <class Arch>
void rbrief_describe_gather(ImageView blurred, const PixelPoint* points, const float* angle_deg, int n,
                            std::uint8_t* descriptors) {
  const rbrief_detail::SplitPattern& pattern = rbrief_detail::split_pattern();
  const float kRadiansPerDegree = static_cast<float>(3.14159265358979323846 / 180.0);
  const int step = static_cast<int>(blurred.stride);
  for (int k = 0; k < n; ++k) {
    const float angle = angle_deg[k] * kRadiansPerDegree;
    const float a = static_cast<float>(std::cos(angle)), b = static_cast<float>(std::sin(angle));
    const std::uint8_t* center = blurred.row(points[k].y) + points[k].x;
    std::uint8_t* out = descriptors + static_cast<std::ptrdiff_t>(k) * 32;
    if constexpr (std::is_base_of_v<xsimd::avx512bw, Arch>) {
      const __m512 va = _mm512_set1_ps(a), vb = _mm512_set1_ps(b);
      const __m512i vstep = _mm512_set1_epi32(step), low_byte = _mm512_set1_epi32(0xff);
      const auto sample = [&](const float* xs, const float* ys, int i) {
        const __m512 x = _mm512_load_ps(xs + i), y = _mm512_load_ps(ys + i);
        const __m512i dx = _mm512_cvtps_epi32(_mm512_sub_ps(_mm512_mul_ps(x, va), _mm512_mul_ps(y, vb)));
        const __m512i dy = _mm512_cvtps_epi32(_mm512_add_ps(_mm512_mul_ps(x, vb), _mm512_mul_ps(y, va)));
        const __m512i offset = _mm512_add_epi32(_mm512_mullo_epi32(dy, vstep), dx);
        return _mm512_and_si512(_mm512_i32gather_epi32(offset, center, 1), low_byte);
      };
      for (int i = 0; i < 256; i += 16) {
        const std::uint16_t bits = static_cast<std::uint16_t>(
            _mm512_cmplt_epi32_mask(sample(pattern.px, pattern.py, i), sample(pattern.qx, pattern.qy, i)));
        std::memcpy(out + i / 8, &bits, sizeof bits);  // little-endian: tests i .. i + 7 first
      }
    } else {
      static_assert(std::is_base_of_v<xsimd::avx2, Arch>, "gathers need AVX2");
      const __m256 va = _mm256_set1_ps(a), vb = _mm256_set1_ps(b);
      const __m256i vstep = _mm256_set1_epi32(step), low_byte = _mm256_set1_epi32(0xff);
      const auto sample = [&](const float* xs, const float* ys, int i) {
        const __m256 x = _mm256_load_ps(xs + i), y = _mm256_load_ps(ys + i);
        const __m256i dx = _mm256_cvtps_epi32(_mm256_sub_ps(_mm256_mul_ps(x, va), _mm256_mul_ps(y, vb)));
        const __m256i dy = _mm256_cvtps_epi32(_mm256_add_ps(_mm256_mul_ps(x, vb), _mm256_mul_ps(y, va)));
        const __m256i offset = _mm256_add_epi32(_mm256_mullo_epi32(dy, vstep), dx);
        return _mm256_and_si256(_mm256_i32gather_epi32(reinterpret_cast<const int*>(center), offset, 1), low_byte);
      };
      for (int i = 0; i < 256; i += 8) {
        const __m256i p_less = _mm256_cmpgt_epi32(sample(pattern.qx, pattern.qy, i), sample(pattern.px, pattern.py, i));
        out[i / 8] = static_cast<std::uint8_t>(_mm256_movemask_ps(_mm256_castsi256_ps(p_less)));
      }
    }
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

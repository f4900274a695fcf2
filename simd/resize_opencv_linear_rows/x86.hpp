#pragma once
// cv::resize INTER_LINEAR's 8-bit arithmetic, vectorised: the contract of
// core/kernels/resize_opencv_linear_rows.hpp, the same bytes, on SSE4.2, AVX2 and AVX-512 (which
// runs the 256-bit form).
//
// Horizontal pass, 8 outputs per 128-bit lane: the plan's x groups say which 16 source bytes
// they read; one pshufb per half puts the two taps of 4 outputs into u16 lanes and pmaddwd with
// (a0, a1) gives, in 32-bit lanes, exactly h = row[s] a0 + row[s1] a1; an arithmetic shift by 4
// and a saturating pack (never saturating: h >> 4 <= 32640) give the int16 row the vertical pass
// reads. Vertical pass: pmulhw is OpenCV's v_mul_hi, (h >> 4) b >> 16 exactly; the sum of two
// (<= 2040) plus 2, shifted by 2 and packed unsigned, is v_rshr_pack_u<2>. AVX2 runs two groups
// per 256-bit register (pshufb stays within 128-bit lanes, so each lane keeps its own window).
// The outputs after the last group take the scalar horizontal span; the vertical pass ends on
// one overlapping vector.
#include <cstdint>
#include <type_traits>

#include "core/kernels/resize_opencv_linear_rows.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace resize_opencv_linear_rows_detail {

// h >> 4 of 4 outputs per 128-bit lane, in 32-bit lanes.
template <class Arch>
inline __m128i horizontal4(__m128i window, __m128i shuffle, __m128i coef) {
  return _mm_srai_epi32(_mm_madd_epi16(_mm_shuffle_epi8(window, shuffle), coef), 4);
}

template <class Arch>
inline __m256i horizontal4(__m256i window, __m256i shuffle, __m256i coef) {
  return _mm256_srai_epi32(_mm256_madd_epi16(_mm256_shuffle_epi8(window, shuffle), coef), 4);
}

template <class Arch>
void horizontal_row(const std::uint8_t* row, const OpenCvResizePlan& plan, std::int16_t* out) {
  constexpr bool kAvx2 = std::is_base_of_v<xsimd::avx2, Arch>;
  const int groups = plan.x_groups;
  const std::int32_t* start = plan.x_group_start.data();
  const std::uint8_t* shuffle[2] = {plan.x_group_shuffle.data(),
                                    plan.x_group_shuffle.data() + 16 * groups};
  const std::int16_t* coef[2] = {plan.x_group_coef.data(), plan.x_group_coef.data() + 8 * groups};
  int g = 0;
  if constexpr (kAvx2) {
    for (; g + 2 <= groups; g += 2) {  // groups g and g + 1, one per 128-bit lane
      const __m256i window =
          _mm256_inserti128_si256(_mm256_castsi128_si256(load16<Arch>(row + start[g])),
                                  load16<Arch>(row + start[g + 1]), 1);
      const __m256i low = horizontal4<Arch>(window, load32<Arch>(shuffle[0] + 16 * g),
                                            load32<Arch>(coef[0] + 8 * g));
      const __m256i high = horizontal4<Arch>(window, load32<Arch>(shuffle[1] + 16 * g),
                                             load32<Arch>(coef[1] + 8 * g));
      // Per lane: outputs 0..3, 4..7 of its group, so the lanes are outputs 8g .. 8g + 15.
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 8 * g), _mm256_packs_epi32(low, high));
    }
  }
  for (; g < groups; ++g) {
    const __m128i window = load16<Arch>(row + start[g]);
    const __m128i low =
        horizontal4<Arch>(window, load16<Arch>(shuffle[0] + 16 * g), load16<Arch>(coef[0] + 8 * g));
    const __m128i high =
        horizontal4<Arch>(window, load16<Arch>(shuffle[1] + 16 * g), load16<Arch>(coef[1] + 8 * g));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 8 * g), _mm_packs_epi32(low, high));
  }
  resize_opencv_horizontal_span_scalar(row, plan, 8 * groups, plan.dst_width, out);
}

template <class Arch>
void vertical_row(const std::int16_t* top, const std::int16_t* bottom, std::int16_t b0,
                  std::int16_t b1, int width, std::uint8_t* out) {
  constexpr bool kAvx2 = std::is_base_of_v<xsimd::avx2, Arch>;
  const __m128i two = _mm_set1_epi16(2), c0 = _mm_set1_epi16(b0), c1 = _mm_set1_epi16(b1);
  int x = 0;
  if constexpr (kAvx2) {
    const __m256i two2 = _mm256_set1_epi16(2), c02 = _mm256_set1_epi16(b0),
                  c12 = _mm256_set1_epi16(b1);
    for (; x + 16 <= width; x += 16) {
      const __m256i sum = _mm256_add_epi16(_mm256_mulhi_epi16(load32<Arch>(top + x), c02),
                                           _mm256_mulhi_epi16(load32<Arch>(bottom + x), c12));
      const __m256i v = _mm256_srai_epi16(_mm256_add_epi16(sum, two2), 2);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x),
                       _mm_packus_epi16(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1)));
    }
  }
  const auto eight = [&](int at) {
    const __m128i sum = _mm_add_epi16(_mm_mulhi_epi16(load16<Arch>(top + at), c0),
                                      _mm_mulhi_epi16(load16<Arch>(bottom + at), c1));
    const __m128i v = _mm_srai_epi16(_mm_add_epi16(sum, two), 2);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + at), _mm_packus_epi16(v, v));
  };
  for (; x + 8 <= width; x += 8) eight(x);
  if (x < width && width >= 8)
    eight(width - 8);  // the last 8 again, overlapping: the same values where they overlap
  else
    resize_opencv_vertical_span_scalar(top, bottom, b0, b1, x, width, out);
}

}  // namespace resize_opencv_linear_rows_detail

template <class Arch>
void resize_opencv_linear_rows(ImageView src, const OpenCvResizePlan& plan, MutableImageView dst,
                               int y_begin, int y_end) {
  using namespace resize_opencv_linear_rows_detail;
  resize_opencv_rows_with(
      src, plan, dst, y_begin, y_end,
      [&](const std::uint8_t* row, std::int16_t* out) { horizontal_row<Arch>(row, plan, out); },
      [&](const std::int16_t* top, const std::int16_t* bottom, std::int16_t b0, std::int16_t b1,
          std::uint8_t* out) { vertical_row<Arch>(top, bottom, b0, b1, plan.dst_width, out); });
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// cv::resize INTER_LINEAR's 8-bit arithmetic on AArch64 NEON: the contract of
// core/kernels/resize_opencv_linear_rows.hpp, the same bytes. The passes of
// simd/resize_opencv_linear_rows/x86.hpp (read its header) with NEON's equivalents: the plan's
// pshufb masks drive tbl (vqtbl1q_u8; its 0x80 lanes read 0 in both), pmaddwd is
// multiply_add_pairs, and pmulhw is a widening multiply (smull, exact) narrowed by an arithmetic
// shift of 16 (shrn), (h >> 4) b >> 16 exactly.
#include <cstdint>

#include <arm_neon.h>

#include "core/kernels/resize_opencv_linear_rows.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace resize_opencv_linear_rows_detail {

// h >> 4 of 4 outputs, in 32-bit lanes.
inline int32x4_t horizontal4(uint8x16_t window, uint8x16_t shuffle, int16x8_t coef) {
  return vshrq_n_s32(multiply_add_pairs(vreinterpretq_s16_u8(vqtbl1q_u8(window, shuffle)), coef),
                     4);
}

// (v b) >> 16 of 8 int16 lanes: OpenCV's v_mul_hi.
inline int16x8_t multiply_high(int16x8_t v, int16x4_t b) {
  return vcombine_s16(vshrn_n_s32(vmull_s16(vget_low_s16(v), b), 16),
                      vshrn_n_s32(vmull_s16(vget_high_s16(v), b), 16));
}

}  // namespace resize_opencv_linear_rows_detail

template <class Arch>
void resize_opencv_linear_rows(ImageView src, const OpenCvResizePlan& plan, MutableImageView dst,
                               int y_begin, int y_end) {
  using namespace resize_opencv_linear_rows_detail;
  const int width = plan.dst_width, groups = plan.x_groups;
  const std::int32_t* start = plan.x_group_start.data();
  const std::uint8_t* shuffle[2] = {plan.x_group_shuffle.data(),
                                    plan.x_group_shuffle.data() + 16 * groups};
  const std::int16_t* coef[2] = {plan.x_group_coef.data(), plan.x_group_coef.data() + 8 * groups};
  const auto horizontal = [&](const std::uint8_t* row, std::int16_t* out) {
    for (int g = 0; g < groups; ++g) {
      const uint8x16_t window = vld1q_u8(row + start[g]);
      const int32x4_t low =
          horizontal4(window, vld1q_u8(shuffle[0] + 16 * g), vld1q_s16(coef[0] + 8 * g));
      const int32x4_t high =
          horizontal4(window, vld1q_u8(shuffle[1] + 16 * g), vld1q_s16(coef[1] + 8 * g));
      vst1q_s16(out + 8 * g, vcombine_s16(vmovn_s32(low), vmovn_s32(high)));  // exact: <= 32640
    }
    resize_opencv_horizontal_span_scalar(row, plan, 8 * groups, width, out);
  };
  const auto vertical = [&](const std::int16_t* top, const std::int16_t* bottom, std::int16_t b0,
                            std::int16_t b1, std::uint8_t* out) {
    const int16x4_t c0 = vdup_n_s16(b0), c1 = vdup_n_s16(b1);
    int x = 0;
    const auto eight = [&](int at) {
      const int16x8_t sum = vaddq_s16(multiply_high(vld1q_s16(top + at), c0),
                                      multiply_high(vld1q_s16(bottom + at), c1));
      // v_rshr_pack_u<2>: (sum + 2) >> 2, saturated to u8.
      vst1_u8(out + at, vqmovun_s16(vshrq_n_s16(vaddq_s16(sum, vdupq_n_s16(2)), 2)));
    };
    for (; x + 8 <= width; x += 8) eight(x);
    if (x < width && width >= 8)
      eight(width - 8);  // the last 8 again, overlapping: the same values where they overlap
    else
      resize_opencv_vertical_span_scalar(top, bottom, b0, b1, x, width, out);
  };
  resize_opencv_rows_with(src, plan, dst, y_begin, y_end, horizontal, vertical);
}

AIEF_SIMD_NAMESPACE_END

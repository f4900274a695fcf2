#pragma once
// One integral image row, NEON: the contract of core/kernels/integral_image_row.hpp, the same
// entries (simd/integral_image_row_x86.hpp's method at 8 pixels a step: a prefix sum in uint16
// lanes by three shifted adds, widened to uint32, plus the carry and the row above).
#include <arm_neon.h>

#include <cstdint>

#include "core/kernels/integral_image_row.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void integral_image_row(const std::uint8_t* pixels, int width, const std::uint32_t* above,
                        std::uint32_t* out) {
  out[0] = 0;
  int x = 0;
  const uint16x8_t zero = vdupq_n_u16(0);
  uint32x4_t carry = vdupq_n_u32(0);
  for (; x + 8 <= width; x += 8) {
    uint16x8_t p = vmovl_u8(vld1_u8(pixels + x));
    p = vaddq_u16(p, vextq_u16(zero, p, 7));  // lanes shifted up by 1, 2, 4
    p = vaddq_u16(p, vextq_u16(zero, p, 6));
    p = vaddq_u16(p, vextq_u16(zero, p, 4));
    const uint32x4_t low = vaddq_u32(vmovl_u16(vget_low_u16(p)), carry);
    const uint32x4_t high = vaddq_u32(vmovl_u16(vget_high_u16(p)), carry);
    carry = vdupq_laneq_u32(high, 3);
    vst1q_u32(out + x + 1, vaddq_u32(low, vld1q_u32(above + x + 1)));
    vst1q_u32(out + x + 5, vaddq_u32(high, vld1q_u32(above + x + 5)));
  }
  std::uint32_t row_sum = vgetq_lane_u32(carry, 0);
  for (; x < width; ++x) {
    row_sum += pixels[x];
    out[x + 1] = above[x + 1] + row_sum;
  }
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// The register layer of one integral image row (simd/integral_image_row/portable.hpp) on AArch64
// NEON, 8 pixels a step: the prefix sum by three adds of the lanes shifted up by 1, 2 and 4.
#include <arm_neon.h>

#include <cstdint>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace integral_image_row_detail {

template <class Arch>
struct Registers {
  static constexpr int kPixels = 8;
  using Carry = uint32x4_t;

  static std::uint32_t row_sum(Carry carry) { return vgetq_lane_u32(carry, 0); }

  // Entries out[0, 8) from pixels[0, 8) and above[0, 8); returns the new carry.
  static Carry step(const std::uint8_t* pixels, const std::uint32_t* above, std::uint32_t* out,
                    Carry carry) {
    const uint16x8_t zero = vdupq_n_u16(0);
    uint16x8_t p = vmovl_u8(vld1_u8(pixels));
    p = vaddq_u16(p, vextq_u16(zero, p, 7));
    p = vaddq_u16(p, vextq_u16(zero, p, 6));
    p = vaddq_u16(p, vextq_u16(zero, p, 4));
    const uint32x4_t low = vaddq_u32(vmovl_u16(vget_low_u16(p)), carry);
    const uint32x4_t high = vaddq_u32(vmovl_u16(vget_high_u16(p)), carry);
    vst1q_u32(out, vaddq_u32(low, vld1q_u32(above)));
    vst1q_u32(out + 4, vaddq_u32(high, vld1q_u32(above + 4)));
    return vdupq_laneq_u32(high, 3);
  }
};

}  // namespace integral_image_row_detail

AIEF_SIMD_NAMESPACE_END

#pragma once
// Q8 bilinear downsampling on AArch64 NEON: the contract of core/kernels/resize_bilinear_rows.hpp,
// the same bytes. The arithmetic of simd/resize_bilinear_rows/x86.hpp (read its header for the
// bounds) with NEON's equivalents: the plan's pshufb masks drive tbl (vqtbl1q_u8; its 0x80 lanes
// read 0 in both), pmaddwd is multiply_add_pairs, and the packs are exact narrowings (values
// 0..255).
#include <cstdint>

#include <arm_neon.h>

#include "core/kernels/resize_bilinear_rows.hpp"
#include "simd/resize_bilinear_rows/groups.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace resize_bilinear_rows_detail {

// 4 outputs, in 32-bit lanes: (h0 (256 - wy) + h1 wy + 32768) >> 16 with h0, h1 the horizontal
// sums of the top and bottom row, computed biased so every product fits int16 x int16.
inline uint32x4_t bilinear4(uint8x16_t top, uint8x16_t bottom, uint8x16_t shuffle, int16x8_t wx,
                            int16x8_t wy_pair) {
  const int32x4_t h0 = multiply_add_pairs(vreinterpretq_s16_u8(vqtbl1q_u8(top, shuffle)), wx);
  const int32x4_t h1 = multiply_add_pairs(vreinterpretq_s16_u8(vqtbl1q_u8(bottom, shuffle)), wx);
  const uint32x4_t pair =
      veorq_u32(vorrq_u32(vreinterpretq_u32_s32(h0), vshlq_n_u32(vreinterpretq_u32_s32(h1), 16)),
                vdupq_n_u32(0x80008000u));
  const int32x4_t p = vaddq_s32(multiply_add_pairs(vreinterpretq_s16_u32(pair), wy_pair),
                                vdupq_n_s32((1 << 23) + (1 << 15)));
  return vshrq_n_u32(vreinterpretq_u32_s32(p), 16);
}

}  // namespace resize_bilinear_rows_detail

template <class Arch>
void resize_bilinear_rows(ImageView src, const ResizePlan& plan, MutableImageView dst, int y_begin,
                          int y_end) {
  using resize_bilinear_rows_detail::bilinear4;
  resize_rows_by_groups(
      src, plan, dst, y_begin, y_end,
      [&](const ResizeGroups& groups, const std::uint8_t* top, const std::uint8_t* bottom,
          std::uint32_t wy, std::uint8_t* out) {
        const int16x8_t wy_pair =
            vreinterpretq_s16_u32(vdupq_n_u32(wy << 16 | (256 - wy)));  // int16 (256 - wy, wy)
        for (int g = 0; g < groups.count; ++g) {
          const uint8x16_t t = vld1q_u8(top + groups.start[g]),
                           b = vld1q_u8(bottom + groups.start[g]);
          const uint32x4_t low = bilinear4(t, b, vld1q_u8(groups.shuffle[0] + 16 * g),
                                           vld1q_s16(groups.weight[0] + 8 * g), wy_pair);
          const uint32x4_t high = bilinear4(t, b, vld1q_u8(groups.shuffle[1] + 16 * g),
                                            vld1q_s16(groups.weight[1] + 8 * g), wy_pair);
          vst1_u8(out + 8 * g, vmovn_u16(vcombine_u16(vmovn_u32(low), vmovn_u32(high))));
        }
      });
}

AIEF_SIMD_NAMESPACE_END

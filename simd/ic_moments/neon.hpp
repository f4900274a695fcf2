#pragma once
// Intensity-centroid moments on AArch64 NEON: the contract of core/kernels/ic_moments.hpp, the same
// integers. Each disc row is two 16-byte loads (pixels x-16 .. x+15), masked to the disc. With
// byte i of a load being the pixel at u = i - 16:
//   m10 = sum u I = sum i I - 16 sum I,   m01 = sum v (row sum),
// so one constant weight vector i = 0..31 serves every row: widening multiplies (umull, i I <=
// 31 * 255 fits u16) accumulated pairwise into u32 lanes (uadalp), and the row sums by pairwise
// widening adds (uaddlp). Every step exact, in unsigned lanes until the final signed combination.
#include <cstdint>

#include <arm_neon.h>

#include "core/kernels/ic_moments.hpp"
#include "simd/ic_moments/disc.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void ic_moments(ImageView level, const PixelPoint* points, int n, std::int32_t* m10,
                std::int32_t* m01) {
  alignas(16) std::uint8_t in_disc[kDiscRows][32], index[32];
  for_each_disc_byte([&](int r, int i, int, bool inside) { in_disc[r][i] = inside ? 0xff : 0; });
  for (int i = 0; i < 32; ++i) index[i] = static_cast<std::uint8_t>(i);
  const uint8x16_t index_low = vld1q_u8(index), index_high = vld1q_u8(index + 16);

  for_each_disc_point(level, points, n, m10, m01, [&](int k, const std::uint8_t* top) {
    uint32x4_t sum_ix = vdupq_n_u32(0), sum_i = vdupq_n_u32(0);
    int32x4_t sum_vi = vdupq_n_s32(0);
    for (int r = 0; r < kDiscRows; ++r) {
      const std::uint8_t* row = top + r * level.stride;
      const uint8x16_t low = vandq_u8(vld1q_u8(row), vld1q_u8(in_disc[r]));
      const uint8x16_t high = vandq_u8(vld1q_u8(row + 16), vld1q_u8(in_disc[r] + 16));
      sum_ix = vpadalq_u16(sum_ix, vmull_u8(vget_low_u8(low), vget_low_u8(index_low)));
      sum_ix = vpadalq_u16(sum_ix, vmull_high_u8(low, index_low));
      sum_ix = vpadalq_u16(sum_ix, vmull_u8(vget_low_u8(high), vget_low_u8(index_high)));
      sum_ix = vpadalq_u16(sum_ix, vmull_high_u8(high, index_high));
      const uint32x4_t row_sum = vpaddlq_u16(vaddq_u16(vpaddlq_u8(low), vpaddlq_u8(high)));
      sum_i = vaddq_u32(sum_i, row_sum);
      sum_vi = vmlaq_n_s32(sum_vi, vreinterpretq_s32_u32(row_sum), r - kPatchRadius);
    }
    m10[k] = static_cast<std::int32_t>(vaddvq_u32(sum_ix)) -
             16 * static_cast<std::int32_t>(vaddvq_u32(sum_i));
    m01[k] = vaddvq_s32(sum_vi);
  });
}

AIEF_SIMD_NAMESPACE_END

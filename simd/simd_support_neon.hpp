#pragma once
// lane_bits and any_nonzero (simd/simd_support.hpp) for AArch64 NEON (xsimd::neon64), which has
// no movemask: the comparison's 0xff lanes are masked with their bit weight (1, 2, .. 128 in
// each half) and each half summed across (addv), a common idiom for it.
#include <cstdint>

#include <arm_neon.h>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
inline std::uint64_t lane_bits(const xsimd::batch_bool<std::uint8_t, Arch>& b) {
  static_assert(sizeof(U8<Arch>) == 16, "NEON: 16 byte lanes");
  static constexpr std::uint8_t kWeights[16] = {1, 2, 4, 8, 16, 32, 64, 128,
                                                1, 2, 4, 8, 16, 32, 64, 128};
  const uint8x16_t weighted = vandq_u8(static_cast<uint8x16_t>(b), vld1q_u8(kWeights));
  return static_cast<std::uint64_t>(vaddv_u8(vget_low_u8(weighted))) |
         static_cast<std::uint64_t>(vaddv_u8(vget_high_u8(weighted))) << 8;
}

// The largest lane (umaxv) is non-zero.
template <class Arch>
inline bool any_nonzero(const U8<Arch>& v) {
  return vmaxvq_u8(static_cast<uint8x16_t>(v)) != 0;
}

// x86's pmaddwd, exactly: a0 b0 + a1 b1, a2 b2 + a3 b3, ... in int32 lanes, from two widening
// multiplies (smull, smull2: int16 x int16 -> int32, exact) and a pairwise add (addp). The only
// input that overflows, both pairs -32768 x -32768, no kernel produces.
inline int32x4_t multiply_add_pairs(int16x8_t a, int16x8_t b) {
  return vpaddq_s32(vmull_s16(vget_low_s16(a), vget_low_s16(b)), vmull_high_s16(a, b));
}

// A batch of uint16 lanes from as many bytes (zero-extended), and back (each lane <= 255).
template <class Arch>
inline xsimd::batch<std::uint16_t, Arch> load_widened(const std::uint8_t* p) {
  return vmovl_u8(vld1_u8(p));
}
template <class Arch>
inline void store_narrowed(std::uint8_t* p, const xsimd::batch<std::uint16_t, Arch>& v) {
  vst1_u8(p, vmovn_u16(static_cast<uint16x8_t>(v)));
}

// Two such batches, a then b, in one store.
template <class Arch>
inline void store_narrowed_pair(std::uint8_t* p, const xsimd::batch<std::uint16_t, Arch>& a,
                                const xsimd::batch<std::uint16_t, Arch>& b) {
  vst1q_u8(
      p, vcombine_u8(vmovn_u16(static_cast<uint16x8_t>(a)), vmovn_u16(static_cast<uint16x8_t>(b))));
}

AIEF_SIMD_NAMESPACE_END

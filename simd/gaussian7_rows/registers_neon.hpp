#pragma once
// The register operations of the 7x7 Gaussian (simd/gaussian7_rows/portable.hpp) on AArch64 NEON,
// one 128-bit register, 8 columns a step; pmaddwd is multiply_add_pairs (simd_support_neon.hpp).
#include <cstdint>

#include <arm_neon.h>

#include "simd/gaussian7_rows/bias.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace gaussian7_rows_detail {

template <class Arch>
struct Registers {
  using V = int16x8_t;  // 8 int16 or 4 int32 lanes, as the operation says
  static constexpr int kColumns = 8;
  static constexpr bool kMaskedTail = false;    // the last step of a span overlaps the one before
  static constexpr bool kPairedStores = false;  // each step stores its 8 bytes
  static V columns(const std::uint8_t* p) { return vreinterpretq_s16_u16(vmovl_u8(vld1_u8(p))); }
  static V load(const std::int16_t* p) { return vld1q_s16(p); }
  static void store(std::int16_t* p, V v) { vst1q_s16(p, v); }
  static V set16(int v) { return vdupq_n_s16(static_cast<std::int16_t>(v)); }
  static V set32(int v) { return vreinterpretq_s16_s32(vdupq_n_s32(v)); }
  static V add16(V a, V b) { return vaddq_s16(a, b); }
  static V mul16(V a, V b) { return vmulq_s16(a, b); }
  static V opaque(V v) {
    __asm__("" : "+w"(v));
    return v;
  }
  static V bias(V v) { return vsubq_s16(v, vdupq_n_s16(kBias)); }
  static V madd(V a, V b) { return vreinterpretq_s16_s32(multiply_add_pairs(a, b)); }
  static V add32(V a, V b) {
    return vreinterpretq_s16_s32(vaddq_s32(vreinterpretq_s32_s16(a), vreinterpretq_s32_s16(b)));
  }
  // even = outputs x, x + 2, ...; odd = x + 1, x + 3, ..., each as S + 2^15 - 2^23 in int32
  // lanes: adding 2^23 and shifting down 16 gives the output (0..255). 8 bytes.
  static void store_outputs(std::uint8_t* out, V even, V odd) {
    const uint32x4_t e =
        vshrq_n_u32(vaddq_u32(vreinterpretq_u32_s16(even), vdupq_n_u32(1u << 23)), 16);
    const uint32x4_t o =
        vshrq_n_u32(vaddq_u32(vreinterpretq_u32_s16(odd), vdupq_n_u32(1u << 23)), 16);
    const uint32x4_t pairs = vorrq_u32(e, vshlq_n_u32(o, 8));
    vst1_u8(out,
            vreinterpret_u8_u16(vmovn_u32(pairs)));  // e | o << 8 fits 16 bits: exact narrowing
  }
};

}  // namespace gaussian7_rows_detail

AIEF_SIMD_NAMESPACE_END

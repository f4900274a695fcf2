#pragma once
// The register operations of the 7x7 Gaussian (simd/gaussian7_rows/portable.hpp) on SSE4.1 / AVX2.
#include <cstdint>
#include <type_traits>

#include <immintrin.h>

#include "simd/gaussian7_rows/bias.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace gaussian7_rows_detail {

// What every width has alike, from its intrinsics' prefix P (_mm, _mm256, _mm512), its width B
// and the asm constraint of its registers: the register type, its u16 lanes (kColumns, also the
// outputs of one horizontal step), a barrier the compiler cannot see through (opaque), loads and
// stores of int16 lanes, broadcasts, and the lane-wise arithmetic.
#define AIEF_BLUR_REGISTER_OPERATIONS(P, B, REGISTER)                                             \
  using V = __m##B##i;                                                                            \
  static constexpr int kColumns = B / 16;                                                         \
  static V opaque(V v) {                                                                          \
    __asm__("" : REGISTER(v));                                                                    \
    return v;                                                                                     \
  }                                                                                               \
  static V load(const std::int16_t* p) { return P##_loadu_si##B(reinterpret_cast<const V*>(p)); } \
  static void store(std::int16_t* p, V v) { P##_storeu_si##B(reinterpret_cast<V*>(p), v); }       \
  static V set16(int v) { return P##_set1_epi16(static_cast<short>(v)); }                         \
  static V set32(int v) { return P##_set1_epi32(v); }                                             \
  static V add16(V a, V b) { return P##_add_epi16(a, b); }                                        \
  static V mul16(V a, V b) { return P##_mullo_epi16(a, b); }                                      \
  static V bias(V v) { return P##_sub_epi16(v, P##_set1_epi16(kBias)); }                          \
  static V madd(V a, V b) { return P##_madd_epi16(a, b); }                                        \
  static V add32(V a, V b) { return P##_add_epi32(a, b); }

// The register the kernel runs on: 128-bit (SSE4.1), 256-bit (AVX2) or 512-bit (AVX-512BW).
// Templates on Arch, so every instruction set's copy is its own symbol.
template <class Arch, int kBits = std::is_base_of_v<xsimd::avx512bw, Arch> ? 512
                                  : std::is_base_of_v<xsimd::avx2, Arch>   ? 256
                                                                           : 128>
struct Registers;

template <class Arch>
struct Registers<Arch, 128> {
  AIEF_BLUR_REGISTER_OPERATIONS(_mm, 128, "+x")
  static constexpr bool kMaskedTail = false;   // the last step of a span overlaps the one before
  static constexpr bool kPairedStores = true;  // output_pairs and store_output_pairs
  static V columns(const std::uint8_t* p) {
    return _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
  }
  // even = outputs x, x + 2, ...; odd = x + 1, x + 3, ..., each as S + 2^15 - 2^23 in int32
  // lanes: bits 16..31 hold the output - 128 as an int16, so one arithmetic shift, a word blend
  // and a signed pack give the bytes output - 128 (output ^ 0x80): 8 bytes.
  static void store_outputs(std::uint8_t* out, V even, V odd) {
    const V pairs =
        _mm_blend_epi16(_mm_srai_epi32(even, 16), odd, 0xAA);  // (e - 128, o - 128) per int32
    _mm_storel_epi64(
        reinterpret_cast<__m128i*>(out),
        _mm_xor_si128(_mm_packs_epi16(pairs, pairs), _mm_set1_epi8(static_cast<char>(0x80))));
  }
  // (e - 128, o - 128) per int32 lane, as store_outputs packs them.
  static V output_pairs(V even, V odd) {
    return _mm_blend_epi16(_mm_srai_epi32(even, 16), odd, 0xAA);
  }
  // Two steps' output_pairs packed into one store of 2 * kColumns bytes.
  static void store_output_pairs(std::uint8_t* out, V pairs0, V pairs1) {
    _mm_storeu_si128(
        reinterpret_cast<__m128i*>(out),
        _mm_xor_si128(_mm_packs_epi16(pairs0, pairs1), _mm_set1_epi8(static_cast<char>(0x80))));
  }
};

// Each wider form only where its unit's flags allow it: clang checks the asm operand sizes of
// the opaque() barrier even in a specialization it never instantiates.
#if defined(__AVX2__)
template <class Arch>
struct Registers<Arch, 256> {
  AIEF_BLUR_REGISTER_OPERATIONS(_mm256, 256, "+x")
  static constexpr bool kMaskedTail = false;
  static constexpr bool kPairedStores = true;
  static V columns(const std::uint8_t* p) {
    return _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
  }
  static void store_outputs(std::uint8_t* out, V even, V odd) {
    const V pairs = _mm256_blend_epi16(_mm256_srai_epi32(even, 16), odd, 0xAA);
    const V packed =
        _mm256_permute4x64_epi64(_mm256_packs_epi16(pairs, pairs), 0x08);  // lanes 0, 2
    _mm_storeu_si128(
        reinterpret_cast<__m128i*>(out),
        _mm_xor_si128(_mm256_castsi256_si128(packed), _mm_set1_epi8(static_cast<char>(0x80))));
  }
  static V output_pairs(V even, V odd) {
    return _mm256_blend_epi16(_mm256_srai_epi32(even, 16), odd, 0xAA);
  }
  static void store_output_pairs(std::uint8_t* out, V pairs0, V pairs1) {
    const V packed =  // lanes: pairs0 low, pairs1 low, pairs0 high, pairs1 high; reordered
        _mm256_permute4x64_epi64(_mm256_packs_epi16(pairs0, pairs1), 0xD8);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                        _mm256_xor_si256(packed, _mm256_set1_epi8(static_cast<char>(0x80))));
  }
};

#endif  // __AVX2__

#if defined(__AVX512BW__)
// 32 columns a step. A step's outputs narrow to bytes in order with one vpmovwb, and the last
// step of a span stores only its first n bytes (a masked vpmovwb), so spans need no overlapping
// step and none narrower than 32 outputs falls back to scalar code.
template <class Arch>
struct Registers<Arch, 512> {
  AIEF_BLUR_REGISTER_OPERATIONS(_mm512, 512, "+v")
  static constexpr bool kMaskedTail = true;
  static V columns(const std::uint8_t* p) {
    return _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
  }
  // The outputs in the low byte of each word, in order (the 128-bit form's (e - 128, o - 128)
  // pairs, xor 0x80); vpmovwb narrows them without a lane shuffle.
  static V output_words(V even, V odd) {
    return _mm512_xor_si512(_mm512_mask_blend_epi16(0xAAAAAAAAu, _mm512_srai_epi32(even, 16), odd),
                            _mm512_set1_epi16(0x80));
  }
  static void store_outputs(std::uint8_t* out, V even, V odd) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                        _mm512_cvtepi16_epi8(output_words(even, odd)));
  }
  static void store_outputs_masked(std::uint8_t* out, V even, V odd,
                                   int n) {  // the first n outputs, 0 < n < 32
    _mm512_mask_cvtepi16_storeu_epi8(out, (1u << n) - 1, output_words(even, odd));
  }
};
#endif  // __AVX512BW__

#undef AIEF_BLUR_REGISTER_OPERATIONS

}  // namespace gaussian7_rows_detail

AIEF_SIMD_NAMESPACE_END

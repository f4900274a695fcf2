#pragma once
// Q8 bilinear downsampling, vectorised: the contract of core/kernels/resize_bilinear_rows.hpp, the
// same bytes.
//
// Horizontal first, on the u8 rows, 8 outputs per 128-bit lane. The plan's x groups
// (ResizePlan::x_group_*) say which 16 source bytes the 8 outputs read; one pshufb per half
// puts the left and right tap of 4 outputs into u16 lanes, and pmaddwd with (256 - wx, wx)
// gives, in 32-bit lanes, exactly the scalar
//   h = L (256 - wx) + R wx,   0 <= h <= 65280.
// Vertical: dst = (S + 32768) >> 16 with S = h0 (256 - wy) + h1 wy, which needs 24 bits and
// h0, h1 are too big for pmaddwd's signed 16-bit inputs. Biased by 32768 they fit:
//   p = (h0 - 32768)(256 - wy) + (h1 - 32768) wy = S - 2^23,  |p| <= 2^23,
// one pmaddwd of the pairs (h0 - 32768, h1 - 32768) with (256 - wy, wy): h0 | h1 << 16 with the
// top bit of each half flipped (xor 0x80008000). Then (S + 32768) >> 16 = (p + 2^23 + 2^15) >> 16,
// 0..255, and every step is an exact integer operation: the same bytes as the scalar code.
// AVX2 runs two groups per 256-bit register (pshufb stays within 128-bit lanes, so each lane
// keeps its own 16-byte window). Outputs after the last group are scalar.
#include <cstdint>
#include <type_traits>

#include "core/kernels/resize_bilinear_rows.hpp"
#include "simd/resize_bilinear_rows/groups.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace resize_bilinear_rows_detail {

// 4 outputs per 128-bit lane, in 32-bit lanes: (h0 (256 - wy) + h1 wy + 32768) >> 16 with
// h0, h1 the horizontal sums of the top and bottom row (see the header comment). Written once for
// both widths, from the intrinsics' prefix P (_mm, _mm256) and the register width B.
#define AIEF_RESIZE_BILINEAR4(P, B)                                                            \
  template <class Arch>                                                                        \
  inline __m##B##i bilinear4(__m##B##i top, __m##B##i bottom, __m##B##i shuffle, __m##B##i wx, \
                             __m##B##i wy) {                                                   \
    const __m##B##i h0 = P##_madd_epi16(P##_shuffle_epi8(top, shuffle), wx);                   \
    const __m##B##i h1 = P##_madd_epi16(P##_shuffle_epi8(bottom, shuffle), wx);                \
    const __m##B##i pair = P##_xor_si##B(P##_or_si##B(h0, P##_slli_epi32(h1, 16)),             \
                                         P##_set1_epi32(static_cast<int>(0x80008000u)));       \
    return P##_srli_epi32(                                                                     \
        P##_add_epi32(P##_madd_epi16(pair, wy), P##_set1_epi32((1 << 23) + (1 << 15))), 16);   \
  }
AIEF_RESIZE_BILINEAR4(_mm, 128)
AIEF_RESIZE_BILINEAR4(_mm256, 256)
#undef AIEF_RESIZE_BILINEAR4

}  // namespace resize_bilinear_rows_detail

template <class Arch>
void resize_bilinear_rows(ImageView src, const ResizePlan& plan, MutableImageView dst, int y_begin,
                          int y_end) {
  using namespace resize_bilinear_rows_detail;
  constexpr bool kAvx2 = std::is_base_of_v<xsimd::avx2, Arch>;
  resize_rows_by_groups(
      src, plan, dst, y_begin, y_end,
      [&](const ResizeGroups& groups, const std::uint8_t* top, const std::uint8_t* bottom,
          std::uint32_t wy, std::uint8_t* out) {
        const __m128i wy_pair =
            _mm_set1_epi32(static_cast<int>(wy << 16 | (256 - wy)));  // int16 (256 - wy, wy)
        int g = 0;
        if constexpr (kAvx2) {
          const __m256i wy_pair2 = _mm256_broadcastsi128_si256(wy_pair);
          for (; g + 2 <= groups.count; g += 2) {  // groups g and g + 1, one per 128-bit lane
            const __m256i t =
                _mm256_inserti128_si256(_mm256_castsi128_si256(load16<Arch>(top + groups.start[g])),
                                        load16<Arch>(top + groups.start[g + 1]), 1);
            const __m256i b = _mm256_inserti128_si256(
                _mm256_castsi128_si256(load16<Arch>(bottom + groups.start[g])),
                load16<Arch>(bottom + groups.start[g + 1]), 1);
            __m256i r[2];
            for (int h = 0; h < 2; ++h)
              r[h] = bilinear4<Arch>(
                  t, b,
                  _mm256_loadu_si256(reinterpret_cast<const __m256i*>(groups.shuffle[h] + 16 * g)),
                  _mm256_loadu_si256(reinterpret_cast<const __m256i*>(groups.weight[h] + 8 * g)),
                  wy_pair2);
            const __m256i r16 =
                _mm256_packs_epi32(r[0], r[1]);  // per lane: outputs 0..3, 4..7 of its group
            _mm_storeu_si128(
                reinterpret_cast<__m128i*>(out + 8 * g),
                _mm_packus_epi16(_mm256_castsi256_si128(r16), _mm256_extracti128_si256(r16, 1)));
          }
        }
        for (; g < groups.count; ++g) {
          const __m128i t = load16<Arch>(top + groups.start[g]),
                        b = load16<Arch>(bottom + groups.start[g]);
          __m128i r[2];
          for (int h = 0; h < 2; ++h)
            r[h] = bilinear4<Arch>(t, b, load16<Arch>(groups.shuffle[h] + 16 * g),
                                   load16<Arch>(groups.weight[h] + 8 * g), wy_pair);
          const __m128i r16 = _mm_packs_epi32(r[0], r[1]);
          _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 8 * g), _mm_packus_epi16(r16, r16));
        }
      });
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// FAST-9 score and suppression, vectorised: the contracts of core/fast9.hpp, the same bytes.
//
// Scores of a whole batch of pixels at once, no branch per pixel. With saturating differences,
// the OpenCV score is max over the 16 arcs of 9 of min over the arc of (r_k - p) or of
// (p - r_k), minus 1. Saturating subtraction is monotone, so it moves out of both the min and
// the max: the brighter side is (max over arcs of min over the arc of r) - p, the darker side
// p - (min over arcs of max over the arc of r), one subtraction each instead of 16. Saturation
// changes only arcs whose minimum is <= 0, which never decide a score >= 1, so every score >=
// min_threshold comes out exact, and the rest are written 0 as the contract asks.
//
// The arcs starting at 2j - 1 and 2j share the eight pixels 2j .. 2j + 7, so the best arc is
// the best over j of min(m8_j, max(r_(2j-1), r_(2j+8))) with m8_j the min of the shared eight
// (pairs, then fours, then eights at even starts): 47 min/max per side instead of the 80 of 16
// independent arcs. The darker side is the same with min and max swapped.
#include <cstddef>
#include <cstdint>

#include "core/fast9.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

// Lowest (Lower = true) or highest value of the best arc of 9: max over arcs of the arc's min,
// or min over arcs of the arc's max.
template <class Arch, bool Lower>
inline U8<Arch> best_arc9(const U8<Arch> r[16]) {
  const auto inner = [](const U8<Arch>& a, const U8<Arch>& b) { return Lower ? xsimd::min(a, b) : xsimd::max(a, b); };
  const auto outer = [](const U8<Arch>& a, const U8<Arch>& b) { return Lower ? xsimd::max(a, b) : xsimd::min(a, b); };
  U8<Arch> m2[8], m4[8];
  for (int j = 0; j < 8; ++j) m2[j] = inner(r[2 * j], r[2 * j + 1]);      // pixels 2j, 2j + 1
  for (int j = 0; j < 8; ++j) m4[j] = inner(m2[j], m2[(j + 1) & 7]);     // 2j .. 2j + 3
  U8<Arch> best = inner(inner(m4[0], m4[2]), outer(r[15], r[8]));       // j = 0: arcs at 15 and 0
  for (int j = 1; j < 8; ++j) {
    const U8<Arch> m8 = inner(m4[j], m4[(j + 2) & 7]);                    // 2j .. 2j + 7
    best = outer(best, inner(m8, outer(r[2 * j - 1], r[(2 * j + 8) & 15])));
  }
  return best;
}

template <class Arch>
void fast9_scores_row(const std::uint8_t* center, std::ptrdiff_t stride, int x_begin, int x_end, int min_threshold,
                      std::uint8_t* scores) {
  constexpr int N = static_cast<int>(U8<Arch>::size);
  if (x_end - x_begin < N) {
    fast9_scores_row_scalar(center, stride, x_begin, x_end, min_threshold, scores);
    return;
  }
  std::ptrdiff_t offsets[16];
  for (int k = 0; k < 16; ++k) offsets[k] = kFastRingDy[k] * stride + kFastRingDx[k];
  const U8<Arch> t(static_cast<std::uint8_t>(min_threshold));
  const U8<Arch> one(std::uint8_t(1)), zero(std::uint8_t(0));

  const auto batch_at = [&](int x) {
    const std::uint8_t* p = center + x;
    const U8<Arch> v = U8<Arch>::load_unaligned(p);
    U8<Arch> ring[16];
    for (int k = 0; k < 16; ++k) ring[k] = U8<Arch>::load_unaligned(p + offsets[k]);
    const U8<Arch> brighter = xsimd::ssub(best_arc9<Arch, true>(ring), v);
    const U8<Arch> darker = xsimd::ssub(v, best_arc9<Arch, false>(ring));
    const U8<Arch> best = xsimd::max(brighter, darker);
    // score = best - 1, kept when >= t, i.e. where best - t (saturating) is not 0.
    xsimd::select(xsimd::ssub(best, t) == zero, zero, best - one).store_unaligned(scores + x);
  };
  int x = x_begin;
  for (; x + N <= x_end; x += N) batch_at(x);
  if (x < x_end) batch_at(x_end - N);  // one overlapping last batch: same values rewritten
}

template <class Arch>
int fast9_local_maxima_row(const std::uint8_t* above, const std::uint8_t* row, const std::uint8_t* below, int x_begin,
                           int x_end, std::int32_t* xs) {
  constexpr int N = static_cast<int>(U8<Arch>::size);
  int count = 0;
  int x = x_begin;
  for (; x + N <= x_end; x += N) {
    // s is a strict maximum where s - max(neighbours) (saturating) is not 0.
    const U8<Arch> s = U8<Arch>::load_unaligned(row + x);
    U8<Arch> neighbours = U8<Arch>::load_unaligned(row + x - 1);
    if (!any_nonzero<Arch>(xsimd::ssub(s, neighbours))) continue;  // most of a score row is 0
    neighbours = xsimd::max(neighbours, U8<Arch>::load_unaligned(row + x + 1));
    for (const std::uint8_t* line : {above, below})
      for (int dx = -1; dx <= 1; ++dx) neighbours = xsimd::max(neighbours, U8<Arch>::load_unaligned(line + x + dx));
    const auto keep = xsimd::ssub(s, neighbours) != U8<Arch>(std::uint8_t(0));
    for (std::uint64_t bits = lane_bits<Arch>(keep); bits != 0; bits &= bits - 1)
      xs[count++] = x + __builtin_ctzll(bits);  // a builtin: no shared inline std:: code in arch TUs
  }
  if (x < x_end) count += fast9_local_maxima_row_scalar(above, row, below, x, x_end, xs + count);
  return count;
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

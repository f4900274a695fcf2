#pragma once
// FAST-9 score and suppression, vectorised: the contracts of core/kernels/fast9_scores_row.hpp, the
// same bytes.
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
#include <type_traits>

#include "core/kernels/fast9_scores_row.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

// Lowest (Lower = true) or highest value of the best arc of 9: max over arcs of the arc's min,
// or min over arcs of the arc's max. ring(k) loads ring pixel k: each pixel is loaded where it
// is used (a memory operand of the min/max), which keeps the 16 ring values out of registers.
template <class Arch, bool Lower, class Ring>
inline U8<Arch> best_arc9(const Ring& ring) {
  const auto inner = [](const U8<Arch>& a, const U8<Arch>& b) {
    return Lower ? xsimd::min(a, b) : xsimd::max(a, b);
  };
  const auto outer = [](const U8<Arch>& a, const U8<Arch>& b) {
    return Lower ? xsimd::max(a, b) : xsimd::min(a, b);
  };
  U8<Arch> m2[8], m4[8];
  for (int j = 0; j < 8; ++j) m2[j] = inner(ring(2 * j), ring(2 * j + 1));  // pixels 2j, 2j + 1
  for (int j = 0; j < 8; ++j) m4[j] = inner(m2[j], m2[(j + 1) & 7]);        // 2j .. 2j + 3
  U8<Arch> best = inner(inner(m4[0], m4[2]), outer(ring(15), ring(8)));  // j = 0: arcs at 15 and 0
  for (int j = 1; j < 8; ++j) {
    const U8<Arch> m8 = inner(m4[j], m4[(j + 2) & 7]);  // 2j .. 2j + 7
    best = outer(best, inner(m8, outer(ring(2 * j - 1), ring((2 * j + 8) & 15))));
  }
  return best;
}

template <class Arch>
void fast9_scores_row(const std::uint8_t* center, std::ptrdiff_t stride, int x_begin, int x_end,
                      int min_threshold, std::uint8_t* scores) {
  constexpr int N = static_cast<int>(U8<Arch>::size);
  if (x_end - x_begin < N) {
    fast9_scores_row_scalar(center, stride, x_begin, x_end, min_threshold, scores);
    return;
  }
  // Seven row pointers and constant column offsets: the 16 ring addresses need 8 registers.
  const std::uint8_t* rows[7];
  for (int dy = -3; dy <= 3; ++dy) rows[dy + 3] = center + dy * stride;
  const U8<Arch> t(static_cast<std::uint8_t>(min_threshold));
  const U8<Arch> one(std::uint8_t(1)), zero(std::uint8_t(0));

  const auto batch_at = [&](int x) {
    const auto ring = [&](int k) {
      return U8<Arch>::load_unaligned(rows[kFastRingDy[k] + 3] + x + kFastRingDx[k]);
    };
    const U8<Arch> v = U8<Arch>::load_unaligned(rows[3] + x);
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

AIEF_SIMD_NAMESPACE_END

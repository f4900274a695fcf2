#pragma once
// FAST-9 score and suppression, vectorised: the contracts of core/fast9.hpp, the same bytes.
//
// Scores of a whole batch of pixels at once, no branch per pixel: with saturating differences
// b_k = max(r_k - p, 0) and d_k = max(p - r_k, 0) of the 16 ring pixels, the OpenCV score is
// max over the 16 arcs of 9 of min(arc of b) or min(arc of d), minus 1. Saturation changes only
// arcs whose minimum is <= 0, which never decide a score >= 1, so every score >= min_threshold
// comes out exact, and the rest are written 0 as the contract asks. Sliding minima by doubling:
// min of 2, of 4, of 8, then with the 9th, 4 x 16 byte minima per direction.
#include <cstddef>
#include <cstdint>

#include "core/fast9.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

template <class Arch>
inline U8<Arch> arc9_best(const U8<Arch> s[16]) {
  U8<Arch> m2[16], m4[16];
  for (int k = 0; k < 16; ++k) m2[k] = xsimd::min(s[k], s[(k + 1) & 15]);
  for (int k = 0; k < 16; ++k) m4[k] = xsimd::min(m2[k], m2[(k + 2) & 15]);
  U8<Arch> best(std::uint8_t(0));
  for (int k = 0; k < 16; ++k) {
    const U8<Arch> m8 = xsimd::min(m4[k], m4[(k + 4) & 15]);
    best = xsimd::max(best, xsimd::min(m8, s[(k + 8) & 15]));
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
    const U8<Arch> hi = xsimd::sadd(v, t), lo = xsimd::ssub(v, t);
    // Pre-test on ring pixels 0, 4, 8, 12: an arc of 9 covers two neighbouring ones of them
    // (k and k + 4), so a corner needs such a pair beyond p +- t in one direction. Saturating
    // differences are non-zero exactly where r > p + t (r < p - t): no unsigned compare needed.
    U8<Arch> beyond_bright[4], beyond_dark[4];
    for (int c = 0; c < 4; ++c) {
      const U8<Arch> r = U8<Arch>::load_unaligned(p + offsets[4 * c]);
      beyond_bright[c] = xsimd::ssub(r, hi);
      beyond_dark[c] = xsimd::ssub(lo, r);
    }
    U8<Arch> pairs = zero;
    for (int c = 0; c < 4; ++c)
      pairs = pairs | xsimd::min(beyond_bright[c], beyond_bright[(c + 1) & 3]) |
              xsimd::min(beyond_dark[c], beyond_dark[(c + 1) & 3]);
    if (!any_nonzero<Arch>(pairs)) {
      zero.store_unaligned(scores + x);
      return;
    }
    U8<Arch> bright[16], dark[16];
    for (int k = 0; k < 16; ++k) {
      const U8<Arch> r = U8<Arch>::load_unaligned(p + offsets[k]);
      bright[k] = xsimd::ssub(r, v);
      dark[k] = xsimd::ssub(v, r);
    }
    const U8<Arch> best = xsimd::max(arc9_best<Arch>(bright), arc9_best<Arch>(dark));
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

#pragma once
// FAST-9 score and suppression, vectorised: the contracts of core/kernels/fast9.hpp, the same bytes.
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

#include "core/kernels/fast9.hpp"
#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

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

// The next narrower x86 arch, whose vectors fit a run too short for Arch's (void: none).
template <class Arch>
struct narrower_arch {
  using type = void;
};
#if !defined(__aarch64__)
template <>
struct narrower_arch<xsimd::avx512bw> {
  using type = xsimd::avx2;
};
template <>
struct narrower_arch<xsimd::avx2> {
  using type = xsimd::sse4_2;
};
#endif

template <class Arch>
void fast9_local_maxima_bits(const std::uint8_t* above, const std::uint8_t* row,
                             const std::uint8_t* below, int x_begin, int x_end,
                             int strong_threshold, std::uint64_t* maxima, std::uint64_t* strong) {
  // 16, 32 or 64 lanes, a divisor of 64: the full batches (at x_begin + k N) each fill part of one
  // bit word; only the overlapping last batch (at x_end - N) can straddle two, handled below.
  constexpr int N = static_cast<int>(U8<Arch>::size);
  if (x_end - x_begin < N) {  // a short run (a block or two): narrower vectors, else the reference
    using Narrower = typename narrower_arch<Arch>::type;
    if constexpr (!std::is_void_v<Narrower>)
      fast9_local_maxima_bits<Narrower>(above, row, below, x_begin, x_end, strong_threshold, maxima,
                                        strong);
    else
      fast9_local_maxima_bits_scalar(above, row, below, x_begin, x_end, strong_threshold, maxima,
                                     strong);
    return;
  }
  const int words = fast9_maxima_words(x_end - x_begin);
  const U8<Arch> zero(std::uint8_t(0));
  // Strong where s >= threshold, i.e. s - (threshold - 1) (saturating) is not 0.
  const int strong_floor = strong_threshold < 1     ? 0
                           : strong_threshold > 256 ? 255
                                                    : strong_threshold - 1;
  const U8<Arch> below_strong(static_cast<std::uint8_t>(strong_floor));
  // No early out on a batch without maxima: on textured frames that branch mispredicts more than
  // the 7 loads and maxes it saves (perf on a rendered 640x480 frame, orbslam2 mode).
  const auto kept_at = [&](int x, std::uint64_t& kept_strong) {
    // s is a strict maximum where s - max(neighbours) (saturating) is not 0.
    const U8<Arch> s = U8<Arch>::load_unaligned(row + x);
    U8<Arch> neighbours =
        xsimd::max(U8<Arch>::load_unaligned(row + x - 1), U8<Arch>::load_unaligned(row + x + 1));
    for (const std::uint8_t* line : {above, below})
      for (int dx = -1; dx <= 1; ++dx)
        neighbours = xsimd::max(neighbours, U8<Arch>::load_unaligned(line + x + dx));
    const std::uint64_t kept = lane_bits<Arch>(xsimd::ssub(s, neighbours) != zero);
    kept_strong = kept & lane_bits<Arch>(xsimd::ssub(s, below_strong) != zero);
    return kept;
  };
  // Each word's bits are gathered in registers from its 64 / N batches and stored once: no
  // clearing pass and no read-modify-write of the words (graf, AVX2: 1.68 -> 1.44 M instructions,
  // 2,301 -> 1,034 mispredicted branches).
  const auto word_at = [&](int x, int batches, std::uint64_t& word_strong) {
    std::uint64_t word = 0;
    word_strong = 0;
    for (int j = 0; j < batches; ++j) {
      std::uint64_t kept_strong;
      const std::uint64_t kept = kept_at(x + j * N, kept_strong);
      word |= kept << (j * N);  // N divides 64, j * N < 64
      word_strong |= kept_strong << (j * N);
    }
    return word;
  };
  int x = x_begin, w = 0;
  for (; x + 64 <= x_end; x += 64, ++w) maxima[w] = word_at(x, 64 / N, strong[w]);
  if (w < words) {  // the last, partial word: its full batches, then one overlapping last batch
    const int batches = (x_end - x) / N;
    maxima[w] = word_at(x, batches, strong[w]);
    x += batches * N;
  }
  if (x < x_end) {
    // The overlapping last batch: OR, not store, rewrites bits already set with the same values,
    // and it can straddle two words.
    std::uint64_t kept_strong;
    const std::uint64_t kept = kept_at(x_end - N, kept_strong);
    const int i = x_end - N - x_begin;
    maxima[i >> 6] |= kept << (i & 63);
    strong[i >> 6] |= kept_strong << (i & 63);
    if ((i & 63) + N > 64) {
      maxima[(i >> 6) + 1] |= kept >> (64 - (i & 63));
      strong[(i >> 6) + 1] |= kept_strong >> (64 - (i & 63));
    }
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

#pragma once
// FAST-9 suppression, vectorised: the contract of core/kernels/fast9_local_maxima_bits.hpp, the
// same bits. A pixel is kept where its score minus the largest of its 8 neighbours (saturating)
// is not 0; the lanes' answers become bit words in registers.
#include <cstdint>
#include <type_traits>

#include "core/kernels/fast9_local_maxima_bits.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

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

AIEF_SIMD_NAMESPACE_END

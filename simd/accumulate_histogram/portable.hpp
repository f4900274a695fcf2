#pragma once
// Block histograms: the contract of core/entropy/block_entropy.hpp. Counting is a scatter, which no
// x86 vector set does faster than independent scalar banks; what vectorises is folding the
// banks into the histogram.
//
// The banks hold 16-bit counters: four banks of 256 uint16 are 2 KB to clear and fold per call
// instead of 4 KB, and a 32 x 32 block calls once per block. On 32 x 32 blocks
// (bench accumulate_histogram/<set>/graf_320x240) this runs about 20% faster than 32-bit banks.
// Measured slower: loading 4 or 8 pixels at once and peeling bytes with shifts, 2 or 8 banks,
// 32 pixels per iteration. What is left is about one counter read-modify-write per pixel per
// cycle, the same on random, real and flat images, and the same speed as counting whole levels
// with no per-block clearing at all. A 16-bit counter holds at most 65535, so the pixels are
// counted in chunks of at most that many, each folded into `hist` before the next: any block
// size and any image stay exact.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

namespace accumulate_histogram_detail {

constexpr int kBanks = 4;
constexpr int kMaxChunkPixels = 65535;  // a uint16 bank counter cannot count further

using Banks = std::uint16_t[kBanks][256];

// Counts width x height pixels into the banks; width * height <= kMaxChunkPixels.
inline void count_chunk(const std::uint8_t* data, std::ptrdiff_t stride, int width, int height,
                        Banks& banks) {
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = data + y * stride;
    int x = 0;
    // 16 pixels per iteration: the loop overhead is a fifth of the work at 4 per iteration.
    for (; x + 16 <= width; x += 16)
      for (int i = 0; i < 16; ++i) ++banks[i % kBanks][row[x + i]];
    for (; x < width; ++x) ++banks[x % kBanks][row[x]];
  }
}

// Zeroes the banks with vector stores: memset's `rep stos` was 6% of the kernel's CPU samples
// (its start-up costs more than 2 KB of stores).
template <class Arch>
void clear_banks(Banks& banks) {
  using U16 = xsimd::batch<std::uint16_t, Arch>;
  const U16 zero(std::uint16_t{0});
  for (int b = 0; b < kBanks; ++b)
    for (int k = 0; k < 256; k += static_cast<int>(U16::size)) zero.store_aligned(banks[b] + k);
}

// hist += the sum of the banks.
template <class Arch>
void fold_banks(const Banks& banks, std::uint32_t* hist) {
  using U16 = xsimd::batch<std::uint16_t, Arch>;
  alignas(64) std::uint16_t sum[256];
  for (int k = 0; k < 256; k += static_cast<int>(U16::size)) {
    const U16 s = (U16::load_aligned(banks[0] + k) + U16::load_aligned(banks[1] + k)) +
                  (U16::load_aligned(banks[2] + k) + U16::load_aligned(banks[3] + k));
    s.store_aligned(sum + k);
  }
  for (int k = 0; k < 256; ++k) hist[k] += sum[k];  // widening add: the compiler vectorises it
}

}  // namespace accumulate_histogram_detail

template <class Arch>
void accumulate_histogram(const std::uint8_t* data, std::ptrdiff_t stride, int width, int height,
                          std::uint32_t* hist) {
  using namespace accumulate_histogram_detail;
  alignas(64) Banks banks;
  clear_banks<Arch>(banks);
  // Chunks of whole rows (of row segments, for rows longer than a chunk), each folded before
  // its bank counters could overflow; a 32 x 32 block is one chunk.
  const int segment_width = std::min(width, kMaxChunkPixels);
  for (int x0 = 0; x0 < width; x0 += segment_width) {
    const int w = std::min(segment_width, width - x0);
    const int rows_per_chunk = kMaxChunkPixels / w;
    for (int y0 = 0; y0 < height; y0 += rows_per_chunk) {
      const int rows = std::min(rows_per_chunk, height - y0);
      count_chunk(data + y0 * stride + x0, stride, w, rows, banks);
      fold_banks<Arch>(banks, hist);
      if (y0 + rows < height || x0 + w < width) clear_banks<Arch>(banks);
    }
  }
}

AIEF_SIMD_NAMESPACE_END

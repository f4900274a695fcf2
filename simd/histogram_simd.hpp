#pragma once
// Block histograms: the contract of core/block_entropy.hpp. Counting is a scatter, which no
// x86 vector set does faster than four independent scalar banks (measured: the scalar banks
// run at ~3.4 G pixels/s on graf, memory speed, beside cv::calcHist's 2.2); what vectorises is
// folding the four banks into the histogram, done here in 32-bit lanes.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "simd/simd_support.hpp"

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

template <class Arch>
void accumulate_histogram(const std::uint8_t* data, std::ptrdiff_t stride, int width, int height, std::uint32_t* hist) {
  using U32 = xsimd::batch<std::uint32_t, Arch>;
  alignas(64) std::uint32_t banks[4][256];
  std::memset(banks, 0, sizeof banks);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = data + y * stride;
    int x = 0;
    for (; x + 4 <= width; x += 4) {
      ++banks[0][row[x]];
      ++banks[1][row[x + 1]];
      ++banks[2][row[x + 2]];
      ++banks[3][row[x + 3]];
    }
    for (; x < width; ++x) ++banks[0][row[x]];
  }
  for (int k = 0; k < 256; k += static_cast<int>(U32::size)) {
    const U32 sum = U32::load_aligned(banks[0] + k) + U32::load_aligned(banks[1] + k) + U32::load_aligned(banks[2] + k) +
                    U32::load_aligned(banks[3] + k) + U32::load_unaligned(hist + k);
    sum.store_unaligned(hist + k);
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

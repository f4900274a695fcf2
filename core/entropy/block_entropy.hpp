#pragma once
// Gray histograms of blocks and their entropy (docs/design.md §3, paper Eq. 5-9).
//
// The histogram is the cached primitive: both entropy measures derive from it, so the adaptive
// sweep (docs/design.md §10) never reads a pixel twice. Entropies are exact functions of the
// integer counts: the sums are fixed-point integers (a table of c * log2 c in Q32), so the
// order of accumulation cannot change a bit in any build.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "aief/options.hpp"
#include "core/kernels/accumulate_histogram.hpp"

namespace aief {

// Shannon entropy in bits of a histogram of n = sum(hist) pixels:
//   E = log2(n) - (1/n) * sum_k c_k log2 c_k; 0 when n == 0 or the block is flat; at most 8.
double histogram_entropy_bits(const std::uint32_t* hist);
// The same for a histogram whose pixel count n = sum(hist) the caller knows (a block's area),
// without the pass that sums it.
double histogram_entropy_bits(const std::uint32_t* hist, std::uint64_t pixels);

// The paper's Eq. 5-6 over the pixels the histogram counts: p = f / sum f, E = -sum p log2 p
// (pixels of value 0 add nothing). 0 when every pixel is 0.
double intensity_entropy_bits(const std::uint32_t* hist);

// The measure chosen by the options (EntropyMeasure::off is an error: callers skip entropy).
double entropy_bits(const std::uint32_t* hist, EntropyMeasure measure);
// The same, pixels = sum(hist) given by the caller.
double entropy_bits(const std::uint32_t* hist, std::uint64_t pixels, EntropyMeasure measure);

}  // namespace aief

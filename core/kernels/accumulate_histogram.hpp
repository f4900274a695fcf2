#pragma once
// The count of a block's gray levels, the primitive both entropy measures derive from
// (core/entropy/block_entropy.hpp, docs/design.md §3).
#include <cstddef>
#include <cstdint>

namespace aief {

using Histogram256 = std::uint32_t[256];

// Adds the counts of the width x height pixels at data (row stride `stride`) to hist.
void accumulate_histogram_scalar(const std::uint8_t* data, std::ptrdiff_t stride, int width,
                                 int height, std::uint32_t* hist);

}  // namespace aief

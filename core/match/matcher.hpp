#pragma once
// match_descriptors with the Hamming kernel of a given table (the public function uses the
// best the CPU runs). Bands of rows of the distance matrix run in parallel
// (parallel/scheduler.hpp), each writing its own slots.
#include "aief/match.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

std::vector<Match> match_descriptors(const std::vector<Descriptor>& a,
                                     const std::vector<Descriptor>& b, const MatchOptions& options,
                                     const KernelTable& kernels);

}  // namespace aief

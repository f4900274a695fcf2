#pragma once
// Stage 2 on one level: every block's histogram, entropy (Eq. 8) and uniform flag.
#include <cstdint>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/level/level_blocks.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

// Fills blocks.entropy_bits and blocks.uniform for every block of `grid` over `pixels`. `whole`,
// when not null, gets every block's histogram added (level 0: Eq. 7 is over the whole level).
void compute_block_entropies(ImageView pixels, const BlockGrid& grid, EntropyMeasure measure,
                             const KernelTable& kernels, LevelBlocks& blocks, std::uint32_t* whole);

// Eq. 7: the entropy of the whole level from `whole` (its blocks' histograms, from
// compute_block_entropies) and the border strips the blocks do not cover, which this adds.
double whole_level_entropy_bits(ImageView pixels, EntropyMeasure measure,
                                const KernelTable& kernels, std::uint32_t whole[256]);

}  // namespace aief

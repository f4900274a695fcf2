#pragma once
// A pair-free entropy threshold F for a single frame, from the distribution of its own block
// entropies (`aief extract --threshold auto`, DESIGN.md section 3 extended).
//
// Rule: Otsu's split of the block entropies (the F that best separates the image's low- and
// high-information blocks, histogram of 0.05-bit bins), lowered when needed so that the mask
// keeps at least kAutoMinKeptShare of the blocks: on a scene that is textured everywhere Otsu
// would otherwise cut through the texture itself.
#include <vector>

namespace aief {

inline constexpr double kAutoMinKeptShare = 0.75;

// Reorders `block_entropies_bits` (a selection runs in place, so a frame allocates nothing).
double auto_entropy_threshold(std::vector<double>& block_entropies_bits);

}  // namespace aief

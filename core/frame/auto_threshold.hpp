#pragma once
// A pair-free entropy threshold F for a single frame, from the distribution of its own block
// entropies (`aief extract --entropy-threshold auto`, docs/design.md §4).
//
// Rule: Otsu's split of the block entropies (the F that best separates the image's low- and
// high-information blocks, histogram of 0.05-bit bins), lowered when needed so that the mask
// keeps at least kAutoMinKeptShare of the blocks: on a scene that is textured everywhere Otsu
// would otherwise cut through the texture itself.
//
// With the two-class test (the aief mode), the split is used only when the entropies
// form two classes. Otsu's effectiveness eta = between-class variance at the split / total
// variance says how well one threshold separates them: 2/pi = 0.64 for a normal distribution,
// 0.75 for a uniform one, towards 1 for two distinct populations. Below kAutoMinEffectiveness the
// entropies are one population (a brick wall, gravel, foliage: texture everywhere), there is no
// low-information class to drop, and F = 0 keeps every block (uniform ones aside, see
// auto_threshold_entropies below). 0.75 is the uniform spread: a frame must split better than an
// even spread of entropies, which has no classes, to lose blocks.
#include <vector>

namespace aief {

class FrameAnalysis;

inline constexpr double kAutoMinKeptShare = 0.75;
inline constexpr double kAutoMinEffectiveness = 0.75;

struct AutoThreshold {
  double threshold_bits = 0;  // F
  double effectiveness = 0;   // Otsu's eta at the split, in [0, 1] (0 when all entropies are equal)
};

// Reorders `block_entropies_bits` (a selection runs in place, so a frame allocates nothing).
// `require_two_classes`: F = 0 when eta < kAutoMinEffectiveness.
AutoThreshold auto_entropy_threshold(std::vector<double>& block_entropies_bits,
                                     bool require_two_classes);

// The block entropies the automatic F splits: every block of every level, less the uniform ones
// when the options say so (ExtractorOptions::auto_skips_uniform_blocks): a uniform block (one
// gray level) cannot hold a corner, and the black border of a warped image would otherwise drag
// F to about 0 on one image of a pair only. After every level's entropies.
void auto_threshold_entropies(const FrameAnalysis& analysis, std::vector<double>& entropies);

}  // namespace aief

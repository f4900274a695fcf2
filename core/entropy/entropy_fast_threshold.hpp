#pragma once
// The FAST threshold of a block from its entropy (FastThresholdFrom::entropy, docs/design.md §5,
// "per-block thresholds"): an entropy-guided variant. A block of entropy H bits tries
//   T(H) = fast_min + floor((fast - fast_min) * min(round(256 H), 256 * kFullThresholdBits)
//                           / (256 * kFullThresholdBits))
// first instead of fast_threshold: fast_min at 0 bits, rising linearly (monotone, integers) to
// fast_threshold at kFullThresholdBits and above. The retry rule stays: a block with no maximum
// at T takes every maximum at fast_min. So a low-entropy (weak-texture, dark) block keeps its
// weaker corners beside its strong ones; a textured block detects as before.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "aief/options.hpp"

namespace aief {

// Entropy from which a block keeps fast_threshold: 6 bits, about the median block of the
// bundled photos (their textured blocks hold 6-7.5 bits, sky and walls 2-5).
constexpr int kFullThresholdBits = 6;

inline int entropy_fast_threshold(double entropy_bits, const ExtractorOptions& options) {
  const std::int64_t full = 256 * kFullThresholdBits;
  const std::int64_t h = std::clamp<std::int64_t>(std::llround(entropy_bits * 256.0), 0, full);
  const std::int64_t span = options.fast_threshold - options.fast_min_threshold;
  return options.fast_min_threshold + static_cast<int>(span * h / full);
}

}  // namespace aief

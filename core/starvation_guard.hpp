#pragma once
// The entropy mask must not starve a frame (DESIGN.md section 3, issue 9). Two rules:
// - frame (the paper mode): lower F for the whole frame while all kept blocks together hold
//   fewer candidates than n_features. Blind to a level left empty while others have plenty: with
//   the automatic F, Otsu over all levels' blocks cuts the smooth coarse levels first (levels
//   6-7 of a gravel-like texture got no keypoint, 867 of 1000 delivered).
// - level: each level lowers its own F while its kept blocks hold fewer candidates than its
//   budget N_n, so every level gets N_n whenever its blocks can give it at F = 0.
// And the automatic F leaves uniform blocks out of Otsu's split (they cannot hold a corner; the
// black border of a warped image otherwise drags F to about 0 on one image of a pair only).
#include <vector>

#include "core/frame_analysis.hpp"

namespace aief {

// Step by which a starving frame or level lowers F: the sweep's S_p (DESIGN.md section 3).
inline constexpr double kStarvationStep = 0.2;

// Detects level n at F, then, while the level's kept blocks hold fewer candidates than N_n and
// F > 0, lowers F by kStarvationStep (not below 0) and detects again. Returns the level's F.
double detect_with_level_guard(FrameAnalysis& analysis, int n, double threshold);

// The block entropies the automatic F splits: every block of every level, less the uniform ones
// when the options say so (ExtractorOptions::auto_skips_uniform_blocks). After stage 2.
void auto_threshold_entropies(const FrameAnalysis& analysis, std::vector<double>& entropies);

}  // namespace aief

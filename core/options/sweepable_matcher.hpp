#pragma once
// The matchers the adaptive sweep runs (core/sweep/sweep_matcher.hpp): every MatcherKind but
// guided, which needs the keypoints and two views of a 3D scene, where the sweep scores each
// threshold by its matches' homography. SweepOptions::validate and SweepMatcher both ask.
#include "aief/match.hpp"

namespace aief {

// MatchOptions::validate, then an aief::Error for matcher guided.
void require_sweepable(const MatchOptions& options);

}  // namespace aief

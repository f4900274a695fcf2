#pragma once
// MatcherKind::guided (aief/match.hpp, docs/design.md §9): matching guided by the two views'
// epipolar geometry, for SfM. The seeds are mutual_ratio's matches; a fundamental matrix found
// among them by RANSAC (core/match/fundamental_ransac.hpp) limits each keypoint's candidates to
// the other image's keypoints near its epipolar line, and mutual nearest neighbours with the ratio
// test are taken again among those few. Bands of rows run in parallel (parallel/scheduler.hpp),
// each writing its own slots: any schedule, the same matches.
#include <vector>

#include "aief/features.hpp"
#include "aief/match.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/match/fundamental_ransac.hpp"

namespace aief {

// Seed inliers a fundamental matrix needs before it guides: fewer, and the seeds are the matches.
inline constexpr int kGuidedMinSeedInliers = 15;

// The seeds' RANSAC: a seed is an inlier within 1 px (Sampson), tight because the matrix then
// bounds every keypoint's candidates; fixed seed, so the same features give the same matches.
RansacOptions guided_seed_ransac();

// Mutual nearest neighbours passing options.ratio and options.max_distance among the pairs
// (i, j) whose Sampson distance under F is at most options.epipolar_band_px.
std::vector<Match> match_in_epipolar_band(const Features& a, const Features& b,
                                          const Fundamental& F, const MatchOptions& options);

// MatcherKind::guided with the Hamming kernel of `kernels` for the seeds.
std::vector<Match> match_guided(const Features& a, const Features& b, const MatchOptions& options,
                                const KernelTable& kernels);

}  // namespace aief

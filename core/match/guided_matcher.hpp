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

// What a fundamental matrix needs before it guides: 15 seed inliers (COLMAP's minimum for a
// verified pair) and a fifth of the seeds. Any 8 correspondences fit a matrix, so random seeds
// leave some within 1 px (measured with random pairs in 1000 x 800 images: 11 of 100, 15 of
// 300; the test AMatrixGuidesWithFifteenInliersAndAFifthOfTheSeeds); on castle-P19, the matrices of
// view pairs that do not overlap held 5-19 % of their seeds, and a wrong matrix makes the band
// hand COLMAP hundreds of wrong matches that agree with it (docs/colmap.md). Fewer, and the
// seeds are the matches.
inline constexpr int kGuidedMinSeedInliers = 15;
inline constexpr double kGuidedMinInlierShare = 0.2;

// The seeds' RANSAC: a seed is an inlier within 1 px (Sampson), tight because the matrix then
// bounds every keypoint's candidates; fixed seed, so the same features give the same matches.
RansacOptions guided_seed_ransac();

// Mutual nearest neighbours passing options.ratio and options.max_distance among the pairs
// (i, j) whose Sampson distance under F is at most options.epipolar_band_px.
std::vector<Match> match_in_epipolar_band(const Features& a, const Features& b,
                                          const Fundamental& F, const MatchOptions& options);

// Whether a matrix found with `inliers` of `seeds` seed matches may guide.
bool guides(int inliers, int seeds);

// MatcherKind::guided with the Hamming kernel of `kernels` for the seeds.
std::vector<Match> match_guided(const Features& a, const Features& b, const MatchOptions& options,
                                const KernelTable& kernels);

}  // namespace aief

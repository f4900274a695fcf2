#pragma once
// Brute-force Hamming matching of 256-bit descriptors (docs/design.md §9).
#include <string_view>
#include <vector>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/features.hpp"

namespace aief {

enum class MatcherKind {
  mutual,  // nearest neighbours both ways (cross-check), the default
  ratio,   // Lowe's ratio test: best < ratio * second best
  paper,   // nearest neighbours with distance <= max(2 * min_distance, 30), the paper's filter
  // Both mutual and ratio: the query's nearest train is kept when that train's nearest query is
  // the query (the cross-check) AND best < ratio * second best among the query's trains (the
  // ratio test in the query's direction only; the train's second nearest query is not tested).
  mutual_ratio,
  // Guided by the two views' geometry, for SfM (docs/colmap.md): mutual_ratio's matches seed a
  // fundamental matrix (RANSAC, Sampson distance <= 1 px); then every keypoint is matched again,
  // mutual and ratio test, among the other image's keypoints within epipolar_band_px of its
  // epipolar line, so that a match the whole image's ratio test drops (a repeated facade, a
  // window among windows) is kept when it is the only good one on its line. Needs keypoints:
  // match_features. Without a matrix (fewer than 15 seed inliers, or under a fifth of the seeds),
  // mutual_ratio's matches.
  guided,
};

std::string_view to_string(MatcherKind kind);
MatcherKind parse_matcher_kind(std::string_view name);  // throws aief::Error

struct MatchOptions {
  MatcherKind kind = MatcherKind::mutual;
  double ratio = 0.8;             // Lowe's ratio for ratio and mutual_ratio, in (0, 1]
  int max_distance = 256;         // matches farther than this many bits are dropped (256: none)
  double epipolar_band_px = 1.0;  // guided: a candidate's Sampson distance to the line, at most

  // Throws aief::Error naming the first invalid field and its value.
  void validate() const;
};

struct Match {
  int query = 0;     // index into the first descriptor set
  int train = 0;     // index into the second
  int distance = 0;  // Hamming distance, bits
};

// Throws aief::Error naming both sets ("'a.png' holds box descriptors, 'b.png' rbrief
// descriptors: ...") when their kinds differ: a Hamming distance between an rBRIEF and a box
// descriptor means nothing. Every front end that matches two feature sets (aief match --pairs,
// aief.match on Features, aief merge, aief colmap) asks it first.
void require_same_descriptor(DescriptorKind a, std::string_view what_a, DescriptorKind b,
                             std::string_view what_b);

// Matches of descriptors `a` (queries) into `b`, sorted by query index. For every query the
// nearest train descriptor wins, ties to the lowest index. Throws aief::Error for
// MatcherKind::guided, which needs the keypoints (match_features).
std::vector<Match> match_descriptors(const std::vector<Descriptor>& a,
                                     const std::vector<Descriptor>& b,
                                     const MatchOptions& options = {});

// Matches of the features `a` (queries) into `b`, sorted by query index: match_descriptors on
// their descriptors, or, for MatcherKind::guided, their keypoints' positions too (in aief's
// pixel-centre coordinates, as extracted). Throws aief::Error for guided when a keypoint count
// differs from its descriptor count or a keypoint is not at a finite position.
std::vector<Match> match_features(const Features& a, const Features& b,
                                  const MatchOptions& options = {});

}  // namespace aief

#pragma once
#include <cstdint>
#include <type_traits>

namespace aief {

// A FAST corner that survived suppression, in level pixels. A trivial type (no default member
// values: write Candidate{...}, whose missing fields are 0), so vectors of them copy with memcpy.
struct Candidate {
  std::int32_t x;
  std::int32_t y;
  std::int32_t score;  // FAST score (OpenCV's definition), >= the block's threshold
  // Scores of the four neighbours in the score map (0 where not a corner at fast_min_threshold),
  // for the sub-pixel peak (core/level/keypoint_position.hpp).
  std::uint8_t score_left, score_right, score_up, score_down;
  // Added to the score when candidates are ranked: the four neighbours' scores with
  // CandidateRanking::cross_score (the score map summed over the cross), 0 with peak_score.
  std::int32_t rank_extra;
};
static_assert(std::is_trivial_v<Candidate>);

// A candidate with only a position and a score (its neighbours' scores and rank_extra 0).
inline Candidate candidate_at(std::int32_t x, std::int32_t y, std::int32_t score) {
  return Candidate{x, y, score, 0, 0, 0, 0, 0};
}

// What candidates are ranked by: the score, or the cross sum (ExtractorOptions::candidate_ranking).
inline std::int32_t rank_strength(const Candidate& c) { return c.score + c.rank_extra; }

// The one ranking of candidates (docs/design.md §6): higher strength first, then higher score,
// then y, then x. With rank_extra = 0 (peak_score) that is score, then y, then x.
inline bool stronger(const Candidate& a, const Candidate& b) {
  if (rank_strength(a) != rank_strength(b)) return rank_strength(a) > rank_strength(b);
  if (a.score != b.score) return a.score > b.score;
  if (a.y != b.y) return a.y < b.y;
  return a.x < b.x;
}

// Raster order, the order of keypoints within a level in the output.
inline bool raster_before(const Candidate& a, const Candidate& b) {
  return a.y != b.y ? a.y < b.y : a.x < b.x;
}

}  // namespace aief

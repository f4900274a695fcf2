#pragma once
// The adaptive entropy threshold (docs/design.md §10, paper Eq. 7-11): sweep F over a pair of
// images, keep the F whose matches have the highest correct matching rate (CMR = RANSAC inliers
// / putative matches) among thresholds with at least min_inliers inliers.
//
// The sweep reads every pixel once: pyramids, block entropies, FAST candidates, orientations and
// descriptors are computed at most once per image; a threshold costs a block mask, the
// distribution, matching and RANSAC on the selected points.
#include <memory>
#include <vector>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/features.hpp"
#include "aief/homography.hpp"
#include "aief/image.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"

namespace aief {

struct SweepOptions {
  double first_threshold = 0.0;  // F_0 (docs/design.md §10)
  double step = 0.2;     // S_p; the sweep runs C = ceil(E / S_p) thresholds, E = entropy of A
  int min_inliers = 20;  // a threshold with fewer inliers cannot be chosen
  MatchOptions match;    // mutual nearest neighbours by default
  RansacOptions ransac;  // 3 px, confidence 0.995, fixed seed

  // Throws aief::Error naming the first invalid field and its value.
  void validate() const;
};

// One threshold of the sweep: one row of the curve.
struct SweepPoint {
  double threshold = 0;   // F
  int kept_blocks = 0;    // blocks of image A with entropy > F, all levels
  int kept_blocks_b = 0;  // same for image B
  int keypoints_a = 0;
  int keypoints_b = 0;
  int putative = 0;       // matches before RANSAC
  int inliers = 0;        // RANSAC inliers of the final model (0 when no model)
  double cmr = 0;         // inliers / putative (Eq. 10), 0 when there is no match
  bool eligible = false;  // inliers >= min_inliers
};

struct AdaptResult {
  bool found = false;             // some threshold was eligible
  double threshold = 0;           // the chosen F (first_threshold when none was eligible)
  int chosen_index = -1;          // its row in curve, -1 when none
  double image_entropy_bits = 0;  // E of image A (Eq. 7), sets the number of thresholds
  std::vector<SweepPoint> curve;
  Features features_a;  // at the chosen F
  Features features_b;
  std::vector<Match> matches;  // putative matches at the chosen F
  HomographyResult homography;
};

// The sweep, built once and run on pair after pair (as Extractor on frame after frame): the
// pyramids, descriptor memos, every threshold's features, the matchers' lists and the threads are
// kept between pairs, so pairs of one size allocate almost nothing after the first.
class AdaptiveSweep {
 public:
  // Validates both option sets (throws aief::Error). `options` gives everything but F (its
  // distribution is used as is, and an entropy measure is required: EntropyMeasure::off is an
  // error).
  explicit AdaptiveSweep(const ExtractorOptions& options = {}, const SweepOptions& sweep = {});
  ~AdaptiveSweep();
  AdaptiveSweep(AdaptiveSweep&&) noexcept;
  AdaptiveSweep& operator=(AdaptiveSweep&&) noexcept;

  // The sweep over the pair (a, b).
  AdaptResult run(ImageView a, ImageView b);
  // Same, into `out`, reusing its vectors' storage.
  void run(ImageView a, ImageView b, AdaptResult& out);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One-shot convenience: AdaptiveSweep(options, sweep).run(a, b).
AdaptResult adapt(ImageView a, ImageView b, const ExtractorOptions& options = {},
                  const SweepOptions& sweep = {});

}  // namespace aief

#pragma once
// RANSAC homography, no OpenCV (docs/design.md §9): normalised 4-point DLT, a fixed-seed
// sampler over a canonical order of the matches (same input set, same answer, whatever its
// order), least-squares refit on the inliers and inliers recounted against the final model.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aief/error.hpp"  // what the functions below throw

namespace aief {

struct Point2 {
  double x = 0;
  double y = 0;
};

using Homography = std::array<double, 9>;  // row-major, maps the first image into the second

struct RansacOptions {
  double threshold_px = 3.0;    // inlier when the reprojection error is <= this, pixels
  double confidence = 0.995;    // stop when an all-inlier sample has been drawn this surely
  int max_iterations = 10000;   // upper bound on samples drawn
  std::uint64_t seed = 0x5eed;  // sampler seed: the same seed, the same answer

  // Throws aief::Error naming the first invalid field and its value.
  void validate() const;
};

struct HomographyResult {
  bool found = false;                     // a model with >= 4 inliers exists
  Homography H{};                         // valid when found
  std::vector<std::uint8_t> inlier_mask;  // per input match, in the caller's order
  int inliers = 0;
  std::string failure;  // why not found, e.g. "fewer than 4 matches"
};

// src[i] in the first image corresponds to dst[i] in the second. Throws aief::Error when the
// sizes differ.
HomographyResult find_homography_ransac(const std::vector<Point2>& src,
                                        const std::vector<Point2>& dst,
                                        const RansacOptions& options = {});

Point2 apply_homography(const Homography& H, Point2 p);

// Mean distance between where `estimated` and `truth` send the four corners of a
// width x height image: the homography accuracy of docs/design.md §14.
double mean_corner_error(const Homography& estimated, const Homography& truth, int width,
                         int height);

}  // namespace aief

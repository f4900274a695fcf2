#pragma once
// RANSAC fundamental matrix, no OpenCV (docs/design.md §9), for guided matching: normalised
// 8-point samples with rank 2 enforced, the homography's fixed-seed sampler over the same
// canonical order (same input set, same answer, whatever its order), Sampson distances, and a
// least-squares 8-point refit on the inliers, recounted (core/match/ransac_support.hpp).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aief/homography.hpp"  // Point2, RansacOptions

namespace aief {

// Row-major; x_b^T F x_a = 0 for a in the first image, b in the second.
using Fundamental = std::array<double, 9>;

struct FundamentalResult {
  bool found = false;  // a model with >= 8 inliers exists
  Fundamental F{};     // valid when found, rank 2, scaled so that its Frobenius norm is 1
  std::vector<std::uint8_t> inlier_mask;  // per input correspondence, in the caller's order
  int inliers = 0;
  std::string failure;  // why not found, e.g. "fewer than 8 matches"
};

// Squared Sampson distance (pixels^2) of the correspondence a <-> b under F:
// (b^T F a)^2 / ((Fa)_x^2 + (Fa)_y^2 + (F^T b)_x^2 + (F^T b)_y^2); a correspondence is an inlier
// when it is <= threshold_px^2. NaN never is an inlier.
double sampson_distance_sq(const Fundamental& F, Point2 a, Point2 b);

// a[i] in the first image corresponds to b[i] in the second. Throws aief::Error when the sizes
// differ or the options are invalid.
FundamentalResult find_fundamental_ransac(const std::vector<Point2>& a,
                                          const std::vector<Point2>& b,
                                          const RansacOptions& options = {});

}  // namespace aief

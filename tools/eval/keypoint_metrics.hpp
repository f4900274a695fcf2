#pragma once
// Measures of the keypoints themselves, independent of descriptors (`aief eval`,
// docs/design.md §14).
#include <vector>

#include "aief/homography.hpp"

namespace aief::eval {

// Repeatability as in Mikolajczyk et al. 2005 (and HPatches' detector task), with a distance
// instead of an overlap criterion: of the keypoints of A that the true homography sends inside B
// and of B's keypoints that its inverse sends inside A, the share of A's whose image lies within
// `tolerance_px` of some keypoint of B, over the smaller of the two visible counts (capped at 1).
double repeatability(const std::vector<Point2>& a, const std::vector<Point2>& b,
                     const Homography& a_to_b, int width_a, int height_a, int width_b, int height_b,
                     double tolerance_px = 3.0);

// Spread: the share of the cell_px x cell_px cells of a width x height image (partial cells at the
// right and bottom count) that hold at least one keypoint.
double keypoint_spread(const std::vector<Point2>& points, int width, int height, int cell_px = 32);

// The inverse of a homography (adjugate over determinant).
Homography inverse_homography(const Homography& h);

}  // namespace aief::eval

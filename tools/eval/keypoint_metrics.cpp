#include "tools/eval/keypoint_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace aief::eval {

Homography inverse_homography(const Homography& h) {
  const double a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], i = h[7],
               k = h[8];
  const Homography adjugate = {e * k - f * i, c * i - b * k, b * f - c * e,
                               f * g - d * k, a * k - c * g, c * d - a * f,
                               d * i - e * g, b * g - a * i, a * e - b * d};
  const double det = a * adjugate[0] + b * adjugate[3] + c * adjugate[6];
  Homography inverse{};
  for (int j = 0; j < 9; ++j)
    inverse[static_cast<std::size_t>(j)] = adjugate[static_cast<std::size_t>(j)] / det;
  return inverse;
}

namespace {

bool inside(Point2 p, int width, int height) {
  return p.x >= 0 && p.y >= 0 && p.x <= width - 1 && p.y <= height - 1;
}

}  // namespace

double repeatability(const std::vector<Point2>& a, const std::vector<Point2>& b,
                     const Homography& a_to_b, int width_a, int height_a, int width_b, int height_b,
                     double tolerance_px) {
  const Homography b_to_a = inverse_homography(a_to_b);
  std::vector<Point2> a_in_b;  // images of A's visible keypoints
  for (const Point2& p : a) {
    const Point2 q = apply_homography(a_to_b, p);
    if (inside(q, width_b, height_b)) a_in_b.push_back(q);
  }
  std::vector<Point2> b_visible;
  for (const Point2& p : b)
    if (inside(apply_homography(b_to_a, p), width_a, height_a)) b_visible.push_back(p);
  const std::size_t smaller = std::min(a_in_b.size(), b_visible.size());
  if (smaller == 0) return 0.0;
  const double tolerance2 = tolerance_px * tolerance_px;
  std::size_t repeated = 0;
  for (const Point2& q : a_in_b)
    for (const Point2& p : b_visible)
      if ((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) <= tolerance2) {
        ++repeated;
        break;
      }
  return std::min(1.0, static_cast<double>(repeated) / static_cast<double>(smaller));
}

double keypoint_spread(const std::vector<Point2>& points, int width, int height, int cell_px) {
  const int cols = (width + cell_px - 1) / cell_px, rows = (height + cell_px - 1) / cell_px;
  if (cols <= 0 || rows <= 0) return 0.0;
  std::vector<char> occupied(static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows), 0);
  for (const Point2& p : points) {
    const int c = std::clamp(static_cast<int>(std::floor(p.x / cell_px)), 0, cols - 1);
    const int r = std::clamp(static_cast<int>(std::floor(p.y / cell_px)), 0, rows - 1);
    occupied[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) +
             static_cast<std::size_t>(c)] = 1;
  }
  return static_cast<double>(std::count(occupied.begin(), occupied.end(), 1)) /
         static_cast<double>(occupied.size());
}

}  // namespace aief::eval

#include <algorithm>
#include <array>
#include <cmath>

#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "core/match/ransac_support.hpp"

namespace aief {

namespace {

// apply_homography's arithmetic, inlined into the inlier count (RANSAC's inner loop).
inline Point2 project(const Homography& H, Point2 p) {
  const double w = H[6] * p.x + H[7] * p.y + H[8];
  return {(H[0] * p.x + H[1] * p.y + H[2]) / w, (H[3] * p.x + H[4] * p.y + H[5]) / w};
}

}  // namespace

Point2 apply_homography(const Homography& H, Point2 p) { return project(H, p); }

double mean_corner_error(const Homography& estimated, const Homography& truth, int width,
                         int height) {
  const Point2 corners[4] = {{0, 0},
                             {static_cast<double>(width), 0},
                             {static_cast<double>(width), static_cast<double>(height)},
                             {0, static_cast<double>(height)}};
  double sum = 0;
  for (const Point2& corner : corners) {
    const Point2 a = apply_homography(estimated, corner), b = apply_homography(truth, corner);
    sum += std::hypot(a.x - b.x, a.y - b.y);
  }
  return sum / 4.0;
}

namespace {

using ransac::Normaliser;
using ransac::normaliser_of;

// H_pixels = T_dst^-1 H_normalised T_src.
Homography denormalise(const double h[9], const Normaliser& src, const Normaliser& dst) {
  // T_src = [s 0 -s cx; 0 s -s cy; 0 0 1], T_dst^-1 = [1/s' 0 cx'; 0 1/s' cy'; 0 0 1].
  const double ts[9] = {src.s, 0, -src.s * src.cx, 0, src.s, -src.s * src.cy, 0, 0, 1};
  const double td[9] = {1 / dst.s, 0, dst.cx, 0, 1 / dst.s, dst.cy, 0, 0, 1};
  double tmp[9], out[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      tmp[r * 3 + c] = h[r * 3] * ts[c] + h[r * 3 + 1] * ts[3 + c] + h[r * 3 + 2] * ts[6 + c];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[r * 3 + c] = td[r * 3] * tmp[c] + td[r * 3 + 1] * tmp[3 + c] + td[r * 3 + 2] * tmp[6 + c];
  Homography H;
  const double scale = std::abs(out[8]) > 1e-15 ? out[8] : 1.0;
  for (int k = 0; k < 9; ++k) H[static_cast<std::size_t>(k)] = out[k] / scale;
  return H;
}

// The two DLT rows of a correspondence (x, y) -> (u, v).
void dlt_rows(Point2 p, Point2 q, double r0[9], double r1[9]) {
  const double x = p.x, y = p.y, u = q.x, v = q.y;
  const double a[9] = {x, y, 1, 0, 0, 0, -u * x, -u * y, -u};
  const double b[9] = {0, 0, 0, x, y, 1, -v * x, -v * y, -v};
  std::copy(a, a + 9, r0);
  std::copy(b, b + 9, r1);
}

// Exactly determined 4-point DLT with h33 = 1: Gaussian elimination with partial pivoting.
bool solve_four_points(const Point2 p[4], const Point2 q[4], double h[9]) {
  double m[8][9];
  for (int i = 0; i < 4; ++i) {
    double r0[9], r1[9];
    dlt_rows(p[i], q[i], r0, r1);
    for (int c = 0; c < 8; ++c) {
      m[2 * i][c] = r0[c];
      m[2 * i + 1][c] = r1[c];
    }
    m[2 * i][8] = -r0[8];
    m[2 * i + 1][8] = -r1[8];
  }
  for (int col = 0; col < 8; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 8; ++r)
      if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
    if (std::abs(m[pivot][col]) < 1e-12) return false;
    if (pivot != col)
      for (int c = 0; c < 9; ++c) std::swap(m[pivot][c], m[col][c]);
    for (int r = 0; r < 8; ++r) {
      if (r == col) continue;
      const double f = m[r][col] / m[col][col];
      for (int c = col; c < 9; ++c) m[r][c] -= f * m[col][c];
    }
  }
  for (int k = 0; k < 8; ++k) h[k] = m[k][8] / m[k][k];
  h[8] = 1.0;
  return true;
}

// A^T A of the DLT rows of the correspondences, summed point by point, each point's first row
// before its second, as the plain sum over all 81 entries of both rows, to the bit: the 3 zeros of
// each row (dlt_rows) make products +-0, which leave every partial sum as it is (a sum that
// starts at +0 never becomes -0), and A^T A is symmetric (x * y == y * x), so only the 21 + 21
// nonzero products of the upper triangle are summed and the lower one is mirrored. Returns false,
// leaving a partial sum, when a normalised coordinate is not finite (0 * inf would be NaN there).
bool accumulate_normal_equations(const std::vector<Point2>& src, const std::vector<Point2>& dst,
                                 const std::vector<int>& indices, const Normaliser& ns,
                                 const Normaliser& nd, double ata[9][9]) {
  static constexpr int kFirstRowNonzero[6] = {0, 1, 2, 6, 7, 8};
  static constexpr int kSecondRowNonzero[6] = {3, 4, 5, 6, 7, 8};
  for (int i : indices) {
    const Point2 p = ns.apply(src[static_cast<std::size_t>(i)]),
                 q = nd.apply(dst[static_cast<std::size_t>(i)]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      return false;
    double r0[9], r1[9];
    dlt_rows(p, q, r0, r1);
    for (int a = 0; a < 6; ++a)
      for (int b = a; b < 6; ++b)
        ata[kFirstRowNonzero[a]][kFirstRowNonzero[b]] +=
            r0[kFirstRowNonzero[a]] * r0[kFirstRowNonzero[b]];
    for (int a = 0; a < 6; ++a)
      for (int b = a; b < 6; ++b)
        ata[kSecondRowNonzero[a]][kSecondRowNonzero[b]] +=
            r1[kSecondRowNonzero[a]] * r1[kSecondRowNonzero[b]];
  }
  for (int p = 0; p < 9; ++p)
    for (int q = p + 1; q < 9; ++q) ata[q][p] = ata[p][q];
  return true;
}

// Least-squares normalised DLT over the given correspondences (>= 4).
bool fit_least_squares(const std::vector<Point2>& src, const std::vector<Point2>& dst,
                       const std::vector<int>& indices, Homography& H) {
  const Normaliser ns =
      normaliser_of(indices, [&](int i) { return src[static_cast<std::size_t>(i)]; });
  const Normaliser nd =
      normaliser_of(indices, [&](int i) { return dst[static_cast<std::size_t>(i)]; });
  double ata[9][9] = {};
  if (!accumulate_normal_equations(src, dst, indices, ns, nd, ata)) {
    // A coordinate overflowed in normalisation: the plain sum, products with the zeros included.
    for (auto& row : ata) std::fill(std::begin(row), std::end(row), 0.0);
    for (int i : indices) {
      double r[2][9];
      dlt_rows(ns.apply(src[static_cast<std::size_t>(i)]),
               nd.apply(dst[static_cast<std::size_t>(i)]), r[0], r[1]);
      for (const auto& row : r)
        for (int p = 0; p < 9; ++p)
          for (int q = 0; q < 9; ++q) ata[p][q] += row[p] * row[q];
    }
  }
  double h[9];
  ransac::smallest_eigenvector(ata, h);
  if (std::abs(h[8]) < 1e-12) return false;
  H = denormalise(h, ns, nd);
  for (double value : H)
    if (!std::isfinite(value)) return false;
  return true;
}

double cross(Point2 a, Point2 b, Point2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// A sample is usable when no three of its points are collinear in either image and every
// triangle keeps its orientation (a homography of the visible plane does not mirror it).
bool sample_is_sound(const Point2 p[4], const Point2 q[4]) {
  static constexpr int kTriangles[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& t : kTriangles) {
    const double a = cross(p[t[0]], p[t[1]], p[t[2]]);
    const double b = cross(q[t[0]], q[t[1]], q[t[2]]);
    const auto scale = [](const Point2* s, const int* t3) {
      return std::hypot(s[t3[1]].x - s[t3[0]].x, s[t3[1]].y - s[t3[0]].y) *
             std::hypot(s[t3[2]].x - s[t3[0]].x, s[t3[2]].y - s[t3[0]].y);
    };
    if (std::abs(a) <= 1e-6 * scale(p, t) || std::abs(b) <= 1e-6 * scale(q, t)) return false;
    if ((a > 0) != (b > 0)) return false;
  }
  return true;
}

// Squared reprojection error of correspondence i under H.
double reprojection_error_sq(const Homography& H, const std::vector<Point2>& src,
                             const std::vector<Point2>& dst, int i) {
  const Point2 p = project(H, src[static_cast<std::size_t>(i)]);
  const double dx = p.x - dst[static_cast<std::size_t>(i)].x,
               dy = p.y - dst[static_cast<std::size_t>(i)].y;
  return dx * dx + dy * dy;  // NaN (a point sent to infinity) is never an inlier
}

}  // namespace

HomographyResult find_homography_ransac(const std::vector<Point2>& src,
                                        const std::vector<Point2>& dst,
                                        const RansacOptions& options) {
  options.validate();
  if (src.size() != dst.size())
    throw Error("find_homography_ransac: " + std::to_string(src.size()) + " source points but " +
                std::to_string(dst.size()) + " destination points");
  HomographyResult result;
  result.inlier_mask.assign(src.size(), 0);
  if (const int bad = ransac::first_non_finite(src, dst); bad >= 0) {
    result.failure = "match " + std::to_string(bad) + " has a non-finite coordinate";
    return result;
  }
  if (src.size() < 4) {
    result.failure = "fewer than 4 matches";
    return result;
  }

  const std::vector<int> order = ransac::canonical_order(src, dst);
  const auto error_of = [&](const Homography& H, int i) {
    return reprojection_error_sq(H, src, dst, i);
  };
  const auto solve = [&](const int* pick, Homography& H) {
    Point2 p[4], q[4];
    for (int k = 0; k < 4; ++k) {
      p[k] = src[static_cast<std::size_t>(pick[k])];
      q[k] = dst[static_cast<std::size_t>(pick[k])];
    }
    if (!sample_is_sound(p, q)) return ransac::SampleOutcome::unsound;
    // Normalise the sample, solve, map back.
    const std::array<int, 4> four = {pick[0], pick[1], pick[2], pick[3]};
    const Normaliser ns =
        normaliser_of(four, [&](int i) { return src[static_cast<std::size_t>(i)]; });
    const Normaliser nd =
        normaliser_of(four, [&](int i) { return dst[static_cast<std::size_t>(i)]; });
    Point2 pn[4], qn[4];
    for (int k = 0; k < 4; ++k) {
      pn[k] = ns.apply(p[k]);
      qn[k] = nd.apply(q[k]);
    }
    double h[9];
    if (!solve_four_points(pn, qn, h)) return ransac::SampleOutcome::unsolved;
    H = denormalise(h, ns, nd);
    return ransac::SampleOutcome::solved;
  };
  const ransac::Search<Homography> search =
      ransac::search<4, Homography>(order, options, solve, error_of);
  if (search.best_count < 4) {
    result.failure = search.sound_samples == 0 ? "all samples degenerate (collinear points)"
                                               : "no model with 4 inliers";
    return result;
  }

  Homography best = search.best;
  const auto fit = [&](const std::vector<int>& indices, Homography& H) {
    return fit_least_squares(src, dst, indices, H);
  };
  const double threshold_sq = options.threshold_px * options.threshold_px;
  const std::vector<int> inliers =
      ransac::refit_on_inliers(best, order, threshold_sq, fit, error_of);
  result.found = inliers.size() >= 4;
  result.H = best;
  result.inliers = static_cast<int>(inliers.size());
  for (int i : inliers) result.inlier_mask[static_cast<std::size_t>(i)] = 1;
  if (!result.found) result.failure = "no model with 4 inliers";
  return result;
}

}  // namespace aief

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "aief/error.hpp"
#include "aief/homography.hpp"

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

// Hartley normalisation: centroid to the origin, mean distance sqrt(2). T maps p to T p.
struct Normaliser {
  double cx = 0, cy = 0, s = 1;
  Point2 apply(Point2 p) const { return {(p.x - cx) * s, (p.y - cy) * s}; }
};

template <class Indices, class Get>
Normaliser normaliser_of(const Indices& indices, Get get) {
  Normaliser n;
  double count = 0;
  for (int i : indices) {
    n.cx += get(i).x;
    n.cy += get(i).y;
    ++count;
  }
  n.cx /= count;
  n.cy /= count;
  double mean = 0;
  for (int i : indices) mean += std::hypot(get(i).x - n.cx, get(i).y - n.cy);
  mean /= count;
  n.s = mean > 0 ? std::sqrt(2.0) / mean : 1.0;
  return n;
}

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

// Unit eigenvector of the smallest eigenvalue of a symmetric 9x9 matrix (cyclic Jacobi).
void smallest_eigenvector(double a[9][9], double out[9]) {
  double v[9][9] = {};
  for (int i = 0; i < 9; ++i) v[i][i] = 1;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0;
    for (int p = 0; p < 9; ++p)
      for (int q = p + 1; q < 9; ++q) off += a[p][q] * a[p][q];
    if (off < 1e-30) break;
    for (int p = 0; p < 9; ++p) {
      for (int q = p + 1; q < 9; ++q) {
        if (std::abs(a[p][q]) < 1e-300) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 9; ++k) {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 9; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 9; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int smallest = 0;
  for (int i = 1; i < 9; ++i)
    if (a[i][i] < a[smallest][smallest]) smallest = i;
  for (int k = 0; k < 9; ++k) out[k] = v[k][smallest];
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
  smallest_eigenvector(ata, h);
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

// Inliers of H over `order` (canonical order), and the sum of their squared errors.
int count_inliers(const Homography& H, const std::vector<Point2>& src,
                  const std::vector<Point2>& dst, const std::vector<int>& order,
                  double threshold_sq, std::vector<int>* inliers, double* error_sum) {
  int count = 0;
  double sum = 0;
  if (inliers) inliers->clear();
  for (int i : order) {
    const Point2 p = project(H, src[static_cast<std::size_t>(i)]);
    const double dx = p.x - dst[static_cast<std::size_t>(i)].x,
                 dy = p.y - dst[static_cast<std::size_t>(i)].y;
    const double e = dx * dx + dy * dy;
    if (e <= threshold_sq) {  // NaN (a point sent to infinity) is never an inlier
      ++count;
      sum += e;
      if (inliers) inliers->push_back(i);
    }
  }
  if (error_sum) *error_sum = sum;
  return count;
}

// The inlier count of a hypothesis, or -1 once the points left cannot bring it to `needed`
// (it would be refused anyway); the squared error sum of the inliers when counted to the end.
int count_inliers_reaching(const Homography& H, const std::vector<Point2>& src,
                           const std::vector<Point2>& dst, const std::vector<int>& order,
                           double threshold_sq, int needed, double* error_sum) {
  int count = 0;
  double sum = 0;
  int left = static_cast<int>(order.size());
  for (int i : order) {
    if (count + left < needed) return -1;
    --left;
    const Point2 p = project(H, src[static_cast<std::size_t>(i)]);
    const double dx = p.x - dst[static_cast<std::size_t>(i)].x,
                 dy = p.y - dst[static_cast<std::size_t>(i)].y;
    const double e = dx * dx + dy * dy;
    if (e <= threshold_sq) {
      ++count;
      sum += e;
    }
  }
  *error_sum = sum;
  return count;
}

// splitmix64: a fixed, portable generator (std:: distributions differ between libraries).
struct Sampler {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  int below(int n) {  // uniform in [0, n), rejection of the biased tail
    const std::uint64_t limit = ~0ull - (~0ull % static_cast<std::uint64_t>(n));
    std::uint64_t r;
    do r = next();
    while (r >= limit);
    return static_cast<int>(r % static_cast<std::uint64_t>(n));
  }
};

}  // namespace

HomographyResult find_homography_ransac(const std::vector<Point2>& src,
                                        const std::vector<Point2>& dst,
                                        const RansacOptions& options) {
  options.validate();
  if (src.size() != dst.size())
    throw Error("find_homography_ransac: " + std::to_string(src.size()) + " source points but " +
                std::to_string(dst.size()) + " destination points");
  HomographyResult result;
  const int n = static_cast<int>(src.size());
  result.inlier_mask.assign(src.size(), 0);
  for (int i = 0; i < n; ++i) {
    const Point2 p = src[static_cast<std::size_t>(i)], q = dst[static_cast<std::size_t>(i)];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y)) {
      result.failure = "match " + std::to_string(i) + " has a non-finite coordinate";
      return result;
    }
  }
  if (n < 4) {
    result.failure = "fewer than 4 matches";
    return result;
  }

  // Canonical order: the sampler sees the same sequence whatever order the caller used.
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Point2 &pa = src[static_cast<std::size_t>(a)], &pb = src[static_cast<std::size_t>(b)];
    const Point2 &qa = dst[static_cast<std::size_t>(a)], &qb = dst[static_cast<std::size_t>(b)];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    if (qa.x != qb.x) return qa.x < qb.x;
    if (qa.y != qb.y) return qa.y < qb.y;
    return a < b;
  });

  const double threshold_sq = options.threshold_px * options.threshold_px;
  Sampler sampler{options.seed};
  int best_count = 0;
  double best_error = 0;
  Homography best{};
  long long iterations = options.max_iterations;
  int sound_samples = 0;
  for (long long it = 0; it < iterations; ++it) {
    int pick[4];
    for (int k = 0; k < 4; ++k) {
      bool fresh;
      do {
        pick[k] = order[static_cast<std::size_t>(sampler.below(n))];
        fresh = true;
        for (int j = 0; j < k; ++j) fresh = fresh && pick[j] != pick[k];
      } while (!fresh);
    }
    Point2 p[4], q[4];
    for (int k = 0; k < 4; ++k) {
      p[k] = src[static_cast<std::size_t>(pick[k])];
      q[k] = dst[static_cast<std::size_t>(pick[k])];
    }
    if (!sample_is_sound(p, q)) continue;
    ++sound_samples;
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
    if (!solve_four_points(pn, qn, h)) continue;
    const Homography H = denormalise(h, ns, nd);
    double error = 0;
    // A hypothesis with fewer inliers than the best is never kept: its count may stop early.
    const int count = count_inliers_reaching(H, src, dst, order, threshold_sq, best_count, &error);
    if (count > best_count || (count == best_count && count > 0 && error < best_error)) {
      best_count = count;
      best_error = error;
      best = H;
      // Samples needed so that one is all inliers with the asked confidence.
      const double w = static_cast<double>(count) / n;
      const double p_all = std::pow(w, 4);
      if (p_all >= 1.0) {
        iterations = std::min<long long>(iterations, it + 1);
      } else if (p_all > 0) {
        const double needed = std::log(1 - options.confidence) / std::log(1 - p_all);
        iterations = std::min<long long>(iterations, static_cast<long long>(std::ceil(needed)));
      }
    }
  }
  if (best_count < 4) {
    result.failure = sound_samples == 0 ? "all samples degenerate (collinear points)"
                                        : "no model with 4 inliers";
    return result;
  }

  // Least-squares refit on the inliers, recounted, while the inlier set grows.
  std::vector<int> inliers;
  count_inliers(best, src, dst, order, threshold_sq, &inliers, nullptr);
  for (int round = 0; round < 10; ++round) {
    Homography refit;
    if (!fit_least_squares(src, dst, inliers, refit)) break;
    std::vector<int> refit_inliers;
    count_inliers(refit, src, dst, order, threshold_sq, &refit_inliers, nullptr);
    if (refit_inliers.size() < inliers.size()) break;
    const bool same = refit_inliers == inliers;
    best = refit;
    inliers.swap(refit_inliers);
    if (same) break;
  }
  result.found = inliers.size() >= 4;
  result.H = best;
  result.inliers = static_cast<int>(inliers.size());
  for (int i : inliers) result.inlier_mask[static_cast<std::size_t>(i)] = 1;
  if (!result.found) result.failure = "no model with 4 inliers";
  return result;
}

}  // namespace aief

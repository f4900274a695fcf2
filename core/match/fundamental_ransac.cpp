#include "core/match/fundamental_ransac.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "aief/error.hpp"
#include "core/match/ransac_support.hpp"

namespace aief {

double sampson_distance_sq(const Fundamental& F, Point2 a, Point2 b) {
  const double fa0 = F[0] * a.x + F[1] * a.y + F[2];
  const double fa1 = F[3] * a.x + F[4] * a.y + F[5];
  const double fa2 = F[6] * a.x + F[7] * a.y + F[8];
  const double ftb0 = F[0] * b.x + F[3] * b.y + F[6];
  const double ftb1 = F[1] * b.x + F[4] * b.y + F[7];
  const double residual = b.x * fa0 + b.y * fa1 + fa2;
  return residual * residual / (fa0 * fa0 + fa1 * fa1 + ftb0 * ftb0 + ftb1 * ftb1);
}

namespace {

constexpr int kSampleSize = 8;

// The nearest rank-2 matrix to f in the Frobenius norm: f (I - v v^T) with v the unit eigenvector
// of f^T f's smallest eigenvalue, which zeroes f's smallest singular value.
void enforce_rank_two(double f[9]) {
  double ftf[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) ftf[r][c] = f[r] * f[c] + f[3 + r] * f[3 + c] + f[6 + r] * f[6 + c];
  double v[3];
  ransac::smallest_eigenvector(ftf, v);
  for (int r = 0; r < 3; ++r) {
    const double fv = f[r * 3] * v[0] + f[r * 3 + 1] * v[1] + f[r * 3 + 2] * v[2];
    for (int c = 0; c < 3; ++c) f[r * 3 + c] -= fv * v[c];
  }
}

// F_pixels = T_b^T F_normalised T_a, scaled to Frobenius norm 1; false when not finite.
bool denormalise(const double f[9], const ransac::Normaliser& na, const ransac::Normaliser& nb,
                 Fundamental& F) {
  // T_a = [s 0 -s cx; 0 s -s cy; 0 0 1], T_b^T = [s' 0 0; 0 s' 0; -s' cx' -s' cy' 1].
  const double ta[9] = {na.s, 0, -na.s * na.cx, 0, na.s, -na.s * na.cy, 0, 0, 1};
  const double tbt[9] = {nb.s, 0, 0, 0, nb.s, 0, -nb.s * nb.cx, -nb.s * nb.cy, 1};
  double tmp[9], out[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      tmp[r * 3 + c] = f[r * 3] * ta[c] + f[r * 3 + 1] * ta[3 + c] + f[r * 3 + 2] * ta[6 + c];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[r * 3 + c] =
          tbt[r * 3] * tmp[c] + tbt[r * 3 + 1] * tmp[3 + c] + tbt[r * 3 + 2] * tmp[6 + c];
  double norm = 0;
  for (double value : out) norm += value * value;
  norm = std::sqrt(norm);
  if (!std::isfinite(norm) || norm == 0) return false;
  for (int k = 0; k < 9; ++k) F[static_cast<std::size_t>(k)] = out[k] / norm;
  return true;
}

// Normalised 8-point fit over the given correspondences (>= 8): the smallest eigenvector of the
// normal equations of the rows of b^T F a = 0, rank 2 enforced, mapped back to pixels. False
// when a normalised coordinate or the result is not finite (a degenerate sample).
template <class Indices>
bool fit_eight_point(const std::vector<Point2>& a, const std::vector<Point2>& b,
                     const Indices& indices, Fundamental& F) {
  const ransac::Normaliser na =
      ransac::normaliser_of(indices, [&](int i) { return a[static_cast<std::size_t>(i)]; });
  const ransac::Normaliser nb =
      ransac::normaliser_of(indices, [&](int i) { return b[static_cast<std::size_t>(i)]; });
  double ata[9][9] = {};
  for (int i : indices) {
    const Point2 p = na.apply(a[static_cast<std::size_t>(i)]),
                 q = nb.apply(b[static_cast<std::size_t>(i)]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      return false;
    // The coefficients of F's entries, row-major, in q^T F p.
    const double row[9] = {q.x * p.x, q.x * p.y, q.x, q.y * p.x, q.y * p.y, q.y, p.x, p.y, 1};
    for (int r = 0; r < 9; ++r)
      for (int c = r; c < 9; ++c) ata[r][c] += row[r] * row[c];
  }
  for (int r = 0; r < 9; ++r)
    for (int c = r + 1; c < 9; ++c) ata[c][r] = ata[r][c];
  double f[9];
  ransac::smallest_eigenvector(ata, f);
  enforce_rank_two(f);
  return denormalise(f, na, nb, F);
}

}  // namespace

FundamentalResult find_fundamental_ransac(const std::vector<Point2>& a,
                                          const std::vector<Point2>& b,
                                          const RansacOptions& options) {
  options.validate();
  if (a.size() != b.size())
    throw Error("find_fundamental_ransac: " + std::to_string(a.size()) +
                " points in the first image but " + std::to_string(b.size()) + " in the second");
  FundamentalResult result;
  result.inlier_mask.assign(a.size(), 0);
  if (const int bad = ransac::first_non_finite(a, b); bad >= 0) {
    result.failure = "match " + std::to_string(bad) + " has a non-finite coordinate";
    return result;
  }
  if (a.size() < kSampleSize) {
    result.failure = "fewer than 8 matches";
    return result;
  }

  const std::vector<int> order = ransac::canonical_order(a, b);
  const auto error_of = [&](const Fundamental& F, int i) {
    return sampson_distance_sq(F, a[static_cast<std::size_t>(i)], b[static_cast<std::size_t>(i)]);
  };
  // A sample the solver cannot use (coincident points, overflow) counts as unsound.
  const auto solve = [&](const int* pick, Fundamental& F) {
    std::array<int, kSampleSize> sample;
    std::copy(pick, pick + kSampleSize, sample.begin());
    return fit_eight_point(a, b, sample, F) ? ransac::SampleOutcome::solved
                                            : ransac::SampleOutcome::unsound;
  };
  const ransac::Search<Fundamental> search =
      ransac::search<kSampleSize, Fundamental>(order, options, solve, error_of);
  if (search.best_count < kSampleSize) {
    result.failure =
        search.sound_samples == 0 ? "all samples degenerate" : "no model with 8 inliers";
    return result;
  }

  Fundamental best = search.best;
  const auto fit = [&](const std::vector<int>& indices, Fundamental& F) {
    return fit_eight_point(a, b, indices, F);
  };
  const double threshold_sq = options.threshold_px * options.threshold_px;
  const std::vector<int> inliers =
      ransac::refit_on_inliers(best, order, threshold_sq, fit, error_of);
  result.found = inliers.size() >= kSampleSize;
  result.F = best;
  result.inliers = static_cast<int>(inliers.size());
  for (int i : inliers) result.inlier_mask[static_cast<std::size_t>(i)] = 1;
  if (!result.found) result.failure = "no model with 8 inliers";
  return result;
}

}  // namespace aief

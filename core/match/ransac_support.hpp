#pragma once
// What the RANSAC estimators of core/match/ share (homography_ransac.cpp,
// fundamental_ransac.cpp; docs/design.md §9): Hartley normalisation, the canonical order of the
// correspondences, the fixed-seed sampler and its search loop with the adaptive iteration count,
// the inlier counts, the least-squares refit loop and the symmetric eigen solver.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "aief/homography.hpp"

namespace aief::ransac {

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

// Unit eigenvector of the smallest eigenvalue of a symmetric N x N matrix (cyclic Jacobi); `a`
// is overwritten. N = 9 for the normal equations of the fits, N = 3 for a rank-2 projection.
template <int N>
void smallest_eigenvector(double (&a)[N][N], double (&out)[N]) {
  double v[N][N] = {};
  for (int i = 0; i < N; ++i) v[i][i] = 1;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0;
    for (int p = 0; p < N; ++p)
      for (int q = p + 1; q < N; ++q) off += a[p][q] * a[p][q];
    if (off < 1e-30) break;
    for (int p = 0; p < N; ++p) {
      for (int q = p + 1; q < N; ++q) {
        if (std::abs(a[p][q]) < 1e-300) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < N; ++k) {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < N; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < N; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int smallest = 0;
  for (int i = 1; i < N; ++i)
    if (a[i][i] < a[smallest][smallest]) smallest = i;
  for (int k = 0; k < N; ++k) out[k] = v[k][smallest];
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

// The index of the first correspondence with a non-finite coordinate, or -1.
int first_non_finite(const std::vector<Point2>& a, const std::vector<Point2>& b);

// Canonical order: the sampler sees the same sequence whatever order the caller used.
std::vector<int> canonical_order(const std::vector<Point2>& a, const std::vector<Point2>& b);

// Inliers of a model over `order` (canonical order), and the sum of their squared errors;
// error_of(i) is correspondence i's squared error (NaN is never an inlier).
template <class ErrorOf>
int count_inliers(ErrorOf error_of, const std::vector<int>& order, double threshold_sq,
                  std::vector<int>* inliers, double* error_sum) {
  int count = 0;
  double sum = 0;
  if (inliers) inliers->clear();
  for (int i : order) {
    const double e = error_of(i);
    if (e <= threshold_sq) {
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
template <class ErrorOf>
int count_inliers_reaching(ErrorOf error_of, const std::vector<int>& order, double threshold_sq,
                           int needed, double* error_sum) {
  int count = 0;
  double sum = 0;
  int left = static_cast<int>(order.size());
  for (int i : order) {
    if (count + left < needed) return -1;
    --left;
    const double e = error_of(i);
    if (e <= threshold_sq) {
      ++count;
      sum += e;
    }
  }
  *error_sum = sum;
  return count;
}

// What a minimal solver made of a sample: refused before solving (a degenerate configuration),
// tried without a model, or a model.
enum class SampleOutcome { unsound, unsolved, solved };

template <class Model>
struct Search {
  Model best{};
  int best_count = 0;
  int sound_samples = 0;  // samples not refused as unsound
};

// The hypothesise-and-verify loop: samples of kSize distinct correspondences drawn over `order`
// by the seeded sampler, solve(pick, model) -> SampleOutcome, error_of(model, i) a squared
// error. The best model has the most inliers, ties to the lower squared error sum; the sample
// count adapts to the best inlier ratio w so that one sample is all inliers (w^kSize) with the
// asked confidence.
template <int kSize, class Model, class Solve, class ErrorOf>
Search<Model> search(const std::vector<int>& order, const RansacOptions& options, Solve solve,
                     ErrorOf error_of) {
  const int n = static_cast<int>(order.size());
  const double threshold_sq = options.threshold_px * options.threshold_px;
  Sampler sampler{options.seed};
  Search<Model> found;
  double best_error = 0;
  long long iterations = options.max_iterations;
  for (long long it = 0; it < iterations; ++it) {
    int pick[kSize];
    for (int k = 0; k < kSize; ++k) {
      bool fresh;
      do {
        pick[k] = order[static_cast<std::size_t>(sampler.below(n))];
        fresh = true;
        for (int j = 0; j < k; ++j) fresh = fresh && pick[j] != pick[k];
      } while (!fresh);
    }
    Model model;
    const SampleOutcome outcome = solve(pick, model);
    if (outcome == SampleOutcome::unsound) continue;
    ++found.sound_samples;
    if (outcome == SampleOutcome::unsolved) continue;
    double error = 0;
    // A hypothesis with fewer inliers than the best is never kept: its count may stop early.
    const int count = count_inliers_reaching([&](int i) { return error_of(model, i); }, order,
                                             threshold_sq, found.best_count, &error);
    if (count > found.best_count ||
        (count == found.best_count && count > 0 && error < best_error)) {
      found.best_count = count;
      best_error = error;
      found.best = model;
      const double w = static_cast<double>(count) / n;
      const double p_all = std::pow(w, kSize);
      if (p_all >= 1.0) {
        iterations = std::min<long long>(iterations, it + 1);
      } else if (const double log_miss = std::log(1 - p_all); log_miss < 0) {
        // 1 - p_all rounds to 1 when p_all < 2^-54 (8 inliers of 1000 and w^8): needed would be
        // -inf, and a count beyond long long's range is no bound either.
        const double needed = std::log(1 - options.confidence) / log_miss;
        if (needed < static_cast<double>(iterations))
          iterations = static_cast<long long>(std::ceil(needed));
      }
    }
  }
  return found;
}

// Least-squares refit on the inliers of `model`, recounted, while the inlier set grows (at most
// 10 rounds); fit(indices, model) -> bool. Returns the inliers of the final `model`.
template <class Model, class Fit, class ErrorOf>
std::vector<int> refit_on_inliers(Model& model, const std::vector<int>& order, double threshold_sq,
                                  Fit fit, ErrorOf error_of) {
  std::vector<int> inliers;
  count_inliers([&](int i) { return error_of(model, i); }, order, threshold_sq, &inliers, nullptr);
  for (int round = 0; round < 10; ++round) {
    Model refit;
    if (!fit(inliers, refit)) break;
    std::vector<int> refit_inliers;
    count_inliers([&](int i) { return error_of(refit, i); }, order, threshold_sq, &refit_inliers,
                  nullptr);
    if (refit_inliers.size() < inliers.size()) break;
    const bool same = refit_inliers == inliers;
    model = refit;
    inliers.swap(refit_inliers);
    if (same) break;
  }
  return inliers;
}

}  // namespace aief::ransac

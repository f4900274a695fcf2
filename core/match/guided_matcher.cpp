#include "core/match/guided_matcher.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "aief/error.hpp"
#include "core/kernels/hamming_256_many.hpp"
#include "core/match/band_nearest.hpp"
#include "core/match/matcher.hpp"
#include "parallel/scheduler.hpp"

namespace aief {

namespace {

constexpr int kRowsPerBand = 64;  // queries per parallel piece; fixed, so merging is deterministic

// A keypoint's epipolar line in the other image (a, b, c: a x + b y + c = 0) and the two terms
// of the Sampson denominator its side contributes (a^2 + b^2).
struct Line {
  double a = 0, b = 0, c = 0, norm_sq = 0;
};

// F x for the first image's keypoints (their lines in the second), or F^T x for the second's
// (their lines in the first).
std::vector<Line> epipolar_lines(const std::vector<Keypoint>& keypoints, const Fundamental& F,
                                 bool transposed) {
  const auto f = [&](int row, int col) {
    return transposed ? F[static_cast<std::size_t>(col * 3 + row)]
                      : F[static_cast<std::size_t>(row * 3 + col)];
  };
  std::vector<Line> lines(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const double x = keypoints[i].x, y = keypoints[i].y;
    Line& l = lines[i];
    l.a = f(0, 0) * x + f(0, 1) * y + f(0, 2);
    l.b = f(1, 0) * x + f(1, 1) * y + f(1, 2);
    l.c = f(2, 0) * x + f(2, 1) * y + f(2, 2);
    l.norm_sq = l.a * l.a + l.b * l.b;
  }
  return lines;
}

std::vector<Point2> positions(const Features& f, const std::vector<Match>& matches, bool query) {
  std::vector<Point2> points;
  points.reserve(matches.size());
  for (const Match& m : matches) {
    const Keypoint& kp = f.keypoints[static_cast<std::size_t>(query ? m.query : m.train)];
    points.push_back({kp.x, kp.y});
  }
  return points;
}

}  // namespace

RansacOptions guided_seed_ransac() {
  RansacOptions ransac;
  ransac.threshold_px = 1.0;
  ransac.confidence = 0.9999;
  ransac.max_iterations = 10000;
  return ransac;
}

std::vector<Match> match_in_epipolar_band(const Features& a, const Features& b,
                                          const Fundamental& F, const MatchOptions& options) {
  std::vector<Match> matches;
  if (a.keypoints.empty() || b.keypoints.empty()) return matches;
  const int n_a = static_cast<int>(a.keypoints.size()), n_b = static_cast<int>(b.keypoints.size());
  const std::vector<Line> lines_in_b = epipolar_lines(a.keypoints, F, false);
  const std::vector<Line> lines_in_a = epipolar_lines(b.keypoints, F, true);
  const double band_sq = options.epipolar_band_px * options.epipolar_band_px;
  const int bands = (n_a + kRowsPerBand - 1) / kRowsPerBand;
  std::vector<Nearest> row_nearest(static_cast<std::size_t>(n_a));
  std::vector<int> band_col_distance(static_cast<std::size_t>(bands) * n_b,
                                     std::numeric_limits<int>::max());
  std::vector<int> band_col_best(band_col_distance.size(), -1);

  parallel::Scheduler().for_each(bands, [&](int band) {
    int* col_distance = band_col_distance.data() + static_cast<std::ptrdiff_t>(band) * n_b;
    int* col_best = band_col_best.data() + static_cast<std::ptrdiff_t>(band) * n_b;
    const int end = std::min(n_a, (band + 1) * kRowsPerBand);
    for (int i = band * kRowsPerBand; i < end; ++i) {
      const Line& line = lines_in_b[static_cast<std::size_t>(i)];
      const std::uint8_t* query = a.descriptors[static_cast<std::size_t>(i)].data();
      Nearest nearest;
      for (int j = 0; j < n_b; ++j) {
        const Keypoint& kp = b.keypoints[static_cast<std::size_t>(j)];
        // Sampson's distance squared: (x_b^T F x_a)^2 / (|F x_a|_xy^2 + |F^T x_b|_xy^2).
        const double residual = line.a * kp.x + line.b * kp.y + line.c;
        const double denominator = line.norm_sq + lines_in_a[static_cast<std::size_t>(j)].norm_sq;
        if (!(residual * residual <= band_sq * denominator)) continue;
        const int d = static_cast<int>(
            hamming_256_scalar(query, b.descriptors[static_cast<std::size_t>(j)].data()));
        nearest.offer(d, j);
        if (d < col_distance[j]) {  // rows ascend: ties keep the lower query
          col_distance[j] = d;
          col_best[j] = i;
        }
      }
      row_nearest[static_cast<std::size_t>(i)] = nearest;
    }
  });

  const std::vector<int> col_best =
      merge_band_column_minima(bands, n_b, band_col_distance, band_col_best);

  for (int i = 0; i < n_a; ++i) {
    const Nearest& nearest = row_nearest[static_cast<std::size_t>(i)];
    if (nearest.best < 0 || nearest.best_distance > options.max_distance) continue;
    const bool is_mutual = col_best[static_cast<std::size_t>(nearest.best)] == i;
    const bool passes_ratio =
        static_cast<double>(nearest.best_distance) < options.ratio * nearest.second_distance;
    if (is_mutual && passes_ratio) matches.push_back({i, nearest.best, nearest.best_distance});
  }
  return matches;
}

bool guides(int inliers, int seeds) {
  return inliers >= kGuidedMinSeedInliers &&
         static_cast<double>(inliers) >= kGuidedMinInlierShare * seeds;
}

std::vector<Match> match_guided(const Features& a, const Features& b, const MatchOptions& options,
                                const KernelTable& kernels) {
  MatchOptions seeding = options;
  seeding.kind = MatcherKind::mutual_ratio;
  std::vector<Match> seeds = match_descriptors(a.descriptors, b.descriptors, seeding, kernels);
  if (static_cast<int>(seeds.size()) < kGuidedMinSeedInliers) return seeds;
  const FundamentalResult geometry = find_fundamental_ransac(
      positions(a, seeds, true), positions(b, seeds, false), guided_seed_ransac());
  if (!geometry.found || !guides(geometry.inliers, static_cast<int>(seeds.size()))) return seeds;
  return match_in_epipolar_band(a, b, geometry.F, options);
}

}  // namespace aief

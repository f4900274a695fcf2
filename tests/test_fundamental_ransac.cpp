// RANSAC fundamental matrix (core/match/fundamental_ransac.hpp): two synthetic pinhole cameras
// viewing points at varying depth, exact and with outliers and noise, order independence, bad
// input, and the Sampson distance by hand.
#include "core/match/fundamental_ransac.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "aief/error.hpp"

namespace aief {
namespace {

using Matrix3 = std::array<double, 9>;  // row-major

Matrix3 multiply(const Matrix3& x, const Matrix3& y) {
  Matrix3 out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) out[r * 3 + c] += x[r * 3 + k] * y[k * 3 + c];
  return out;
}

Matrix3 transpose(const Matrix3& x) {
  return {x[0], x[3], x[6], x[1], x[4], x[7], x[2], x[5], x[8]};
}

Matrix3 rotation(double about_x, double about_y, double about_z) {
  const Matrix3 rx = {
      1, 0, 0, 0, std::cos(about_x), -std::sin(about_x), 0, std::sin(about_x), std::cos(about_x)};
  const Matrix3 ry = {std::cos(about_y),  0, std::sin(about_y), 0, 1, 0,
                      -std::sin(about_y), 0, std::cos(about_y)};
  const Matrix3 rz = {
      std::cos(about_z), -std::sin(about_z), 0, std::sin(about_z), std::cos(about_z), 0, 0, 0, 1};
  return multiply(rz, multiply(ry, rx));
}

double determinant(const Matrix3& m) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
         m[2] * (m[3] * m[7] - m[4] * m[6]);
}

double frobenius(const Matrix3& m) {
  double sum = 0;
  for (double v : m) sum += v * v;
  return std::sqrt(sum);
}

// Frobenius norm of the cofactor matrix: the product of the two largest singular values when
// the third is small, so |det| / (|m| |cof m|) is about the smallest over the largest.
double cofactor_norm(const Matrix3& m) {
  double sum = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
      const double minor = m[r0 * 3 + c0] * m[r1 * 3 + c1] - m[r0 * 3 + c1] * m[r1 * 3 + c0];
      sum += minor * minor;
    }
  return std::sqrt(sum);
}

constexpr double kFocal = 1000, kWidth = 1000, kHeight = 800;
const Matrix3 kK = {kFocal, 0, kWidth / 2, 0, kFocal, kHeight / 2, 0, 0, 1};
const Matrix3 kKInverse = {
    1 / kFocal, 0, -kWidth / 2 / kFocal, 0, 1 / kFocal, -kHeight / 2 / kFocal, 0, 0, 1};

// Camera a at the origin looking down +z; camera b sees X as R X + t. Both share K.
struct TwoViews {
  Matrix3 R = rotation(0.05, -0.18, 0.03);
  std::array<double, 3> t = {-1.0, 0.15, 0.2};

  Fundamental truth() const {  // K^-T [t]x R K^-1
    const Matrix3 tx = {0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0};
    const Matrix3 F = multiply(transpose(kKInverse), multiply(multiply(tx, R), kKInverse));
    const double norm = frobenius(F);
    Fundamental out;
    for (int k = 0; k < 9; ++k)
      out[static_cast<std::size_t>(k)] = F[static_cast<std::size_t>(k)] / norm;
    return out;
  }
};

struct Correspondences {
  std::vector<Point2> a, b;
  std::vector<bool> inlier;   // generated from a 3D point (else a random pair)
  std::vector<double> noise;  // distance b was moved by, pixels
};

// `count` 3D points at depths 3..15 seen by both cameras inside the image, b moved by Gaussian
// noise of `sigma` pixels; then `outliers` random pairs; shuffled together.
Correspondences synthetic(const TwoViews& views, int count, int outliers, double sigma,
                          std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, kWidth), v(0, kHeight), depth(3, 15);
  std::normal_distribution<double> jitter(0, sigma > 0 ? sigma : 1);  // unused when 0
  Correspondences s;
  while (static_cast<int>(s.a.size()) < count) {
    const Point2 pa{u(rng), v(rng)};
    const double z = depth(rng);
    const std::array<double, 3> X = {(kKInverse[0] * pa.x + kKInverse[2]) * z,
                                     (kKInverse[4] * pa.y + kKInverse[5]) * z, z};
    std::array<double, 3> Y{};
    for (int r = 0; r < 3; ++r)
      Y[static_cast<std::size_t>(r)] = views.R[r * 3] * X[0] + views.R[r * 3 + 1] * X[1] +
                                       views.R[r * 3 + 2] * X[2] +
                                       views.t[static_cast<std::size_t>(r)];
    if (Y[2] <= 0.1) continue;
    const Point2 pb{kFocal * Y[0] / Y[2] + kWidth / 2, kFocal * Y[1] / Y[2] + kHeight / 2};
    if (pb.x < 0 || pb.x > kWidth || pb.y < 0 || pb.y > kHeight) continue;
    const double dx = sigma > 0 ? jitter(rng) : 0;
    const double dy = sigma > 0 ? jitter(rng) : 0;
    s.a.push_back(pa);
    s.b.push_back({pb.x + dx, pb.y + dy});
    s.inlier.push_back(true);
    s.noise.push_back(std::hypot(dx, dy));
  }
  for (int i = 0; i < outliers; ++i) {
    s.a.push_back({u(rng), v(rng)});
    s.b.push_back({u(rng), v(rng)});
    s.inlier.push_back(false);
    s.noise.push_back(0);
  }
  std::vector<std::size_t> perm(s.a.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  Correspondences shuffled;
  for (std::size_t i : perm) {
    shuffled.a.push_back(s.a[i]);
    shuffled.b.push_back(s.b[i]);
    shuffled.inlier.push_back(s.inlier[i]);
    shuffled.noise.push_back(s.noise[i]);
  }
  return shuffled;
}

TEST(FundamentalRansac, ExactCorrespondencesGiveARankTwoUnitModelThatFitsThemAll) {
  const TwoViews views;
  const Correspondences s = synthetic(views, 200, 0, 0, 3);
  const FundamentalResult result = find_fundamental_ransac(s.a, s.b);
  ASSERT_TRUE(result.found) << result.failure;
  EXPECT_EQ(result.inliers, 200);
  for (std::size_t i = 0; i < s.a.size(); ++i) {
    EXPECT_LT(sampson_distance_sq(result.F, s.a[i], s.b[i]), 1e-6) << i;
    EXPECT_EQ(result.inlier_mask[i], 1) << i;
  }
  EXPECT_NEAR(frobenius(result.F), 1.0, 1e-12);
  // Rank 2, measured on K^T F K (the essential matrix's scale, where F's entries are balanced).
  const Matrix3 E = multiply(transpose(kK), multiply(result.F, kK));
  EXPECT_LT(std::abs(determinant(E)) / (frobenius(E) * cofactor_norm(E)), 1e-12);
}

TEST(FundamentalRansac, FindsTheInliersAmongFortyPercentOutliersWithNoise) {
  const TwoViews views;
  const Fundamental truth = views.truth();
  const Correspondences s = synthetic(views, 200, 133, 0.3, 11);
  RansacOptions options;
  options.threshold_px = 1.0;
  const FundamentalResult result = find_fundamental_ransac(s.a, s.b, options);
  ASSERT_TRUE(result.found) << result.failure;
  int inliers = 0, found_inliers = 0, small_noise = 0, found_small_noise = 0;
  int accepted_outliers = 0;
  for (std::size_t i = 0; i < s.a.size(); ++i) {
    const bool accepted = result.inlier_mask[i] == 1;
    if (s.inlier[i]) {
      ++inliers;
      found_inliers += accepted;
      if (s.noise[i] <= 0.5) {
        ++small_noise;
        found_small_noise += accepted;
      }
    } else if (accepted) {
      ++accepted_outliers;
      // An outlier is accepted only when it happens to lie near its true epipolar geometry.
      EXPECT_LE(sampson_distance_sq(truth, s.a[i], s.b[i]), 1.5 * 1.5) << i;
    }
  }
  EXPECT_GE(found_inliers, 0.95 * inliers);
  EXPECT_GE(found_small_noise, 0.99 * small_noise);
  EXPECT_LE(accepted_outliers, 3);
  EXPECT_EQ(result.inliers, found_inliers + accepted_outliers);
  // Rank 2 also when the least-squares refit of noisy points is full rank.
  const Matrix3 E = multiply(transpose(kK), multiply(result.F, kK));
  EXPECT_LT(std::abs(determinant(E)) / (frobenius(E) * cofactor_norm(E)), 1e-12);
}

TEST(FundamentalRansac, SameAnswerForTheSameInputInAnyOrder) {
  const Correspondences s = synthetic(TwoViews{}, 150, 100, 0.3, 5);
  const FundamentalResult first = find_fundamental_ransac(s.a, s.b);
  const FundamentalResult again = find_fundamental_ransac(s.a, s.b);
  ASSERT_TRUE(first.found) << first.failure;
  EXPECT_EQ(std::memcmp(first.F.data(), again.F.data(), sizeof(Fundamental)), 0);
  EXPECT_EQ(first.inlier_mask, again.inlier_mask);

  std::vector<std::size_t> perm(s.a.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(99));
  std::vector<Point2> a, b;
  for (std::size_t i : perm) {
    a.push_back(s.a[i]);
    b.push_back(s.b[i]);
  }
  const FundamentalResult shuffled = find_fundamental_ransac(a, b);
  ASSERT_TRUE(shuffled.found) << shuffled.failure;
  EXPECT_EQ(std::memcmp(first.F.data(), shuffled.F.data(), sizeof(Fundamental)), 0);
  EXPECT_EQ(shuffled.inliers, first.inliers);
  for (std::size_t j = 0; j < perm.size(); ++j)
    EXPECT_EQ(shuffled.inlier_mask[j], first.inlier_mask[perm[j]]) << j;
}

TEST(FundamentalRansac, BadInputGetsNoModelAndAReasonOrThrows) {
  const Correspondences s = synthetic(TwoViews{}, 20, 0, 0, 7);
  const std::vector<Point2> a7(s.a.begin(), s.a.begin() + 7), b7(s.b.begin(), s.b.begin() + 7);
  const FundamentalResult seven = find_fundamental_ransac(a7, b7);
  EXPECT_FALSE(seven.found);
  EXPECT_EQ(seven.failure, "fewer than 8 matches");
  EXPECT_EQ(seven.inlier_mask, std::vector<std::uint8_t>(7, 0));

  std::vector<Point2> shorter = s.b;
  shorter.pop_back();
  EXPECT_THROW(find_fundamental_ransac(s.a, shorter), Error);

  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::vector<Point2> b = s.b;
    b[5].y = bad;
    const FundamentalResult result = find_fundamental_ransac(s.a, b);
    EXPECT_FALSE(result.found);
    EXPECT_EQ(result.failure, "match 5 has a non-finite coordinate");
    EXPECT_EQ(result.inlier_mask, std::vector<std::uint8_t>(s.a.size(), 0));
  }

  // Finite but so large that normalising overflows: every sample is refused, no crash.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> huge(1e307, 1.7e308);
  std::vector<Point2> huge_a, huge_b;
  for (int i = 0; i < 30; ++i) {
    huge_a.push_back({huge(rng), huge(rng)});
    huge_b.push_back({huge(rng), -huge(rng)});
  }
  const FundamentalResult overflow = find_fundamental_ransac(huge_a, huge_b);
  EXPECT_FALSE(overflow.found);
  EXPECT_EQ(overflow.failure, "all samples degenerate");

  // One correspondence repeated: no epipolar geometry to find.
  const FundamentalResult repeated =
      find_fundamental_ransac(std::vector<Point2>(30, {5, 5}), std::vector<Point2>(30, {7, 9}));
  EXPECT_FALSE(repeated.found);
  EXPECT_FALSE(repeated.failure.empty());

  RansacOptions options;
  options.threshold_px = 0;
  EXPECT_THROW(find_fundamental_ransac(s.a, s.b, options), Error);
  options = {};
  options.confidence = 1;
  EXPECT_THROW(find_fundamental_ransac(s.a, s.b, options), Error);
}

TEST(FundamentalRansac, SampsonDistanceByHand) {
  // Translation along x: epipolar lines are rows; 3 px of vertical disparity split between the
  // two images is 1.5 px each, 4.5 px^2 in all.
  const Fundamental rows = {0, 0, 0, 0, 0, -1, 0, 1, 0};
  EXPECT_DOUBLE_EQ(sampson_distance_sq(rows, {10, 20}, {30, 23}), 4.5);
  // F a = (8, 20, 33), b^T F a = 37, F^T b = (6, 9, .): 37^2 / (64 + 400 + 36 + 81).
  const Fundamental general = {1, 2, 3, 4, 5, 6, 7, 8, 10};
  EXPECT_DOUBLE_EQ(sampson_distance_sq(general, {1, 2}, {3, -1}), 1369.0 / 581.0);
  // No model at all: 0 / 0, which is never an inlier.
  EXPECT_TRUE(std::isnan(sampson_distance_sq(Fundamental{}, {1, 2}, {3, 4})));
}

}  // namespace
}  // namespace aief

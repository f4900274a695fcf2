// RANSAC homography: synthetic truth with outliers, order independence, degenerate input, and
// cv::findHomography as an outside reference on the sample pairs.
#include <fstream>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

Homography read_homography(const std::string& path) {
  std::ifstream in(path);
  Homography H{};
  for (double& v : H) in >> v;
  EXPECT_TRUE(in) << "cannot read " << path;
  return H;
}

struct Synthetic {
  std::vector<Point2> src, dst;
};

Synthetic synthetic(const Homography& H, int inliers, int outliers, double noise,
                    std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0, 800), y(0, 640);
  std::normal_distribution<double> jitter(0, noise);
  Synthetic s;
  for (int i = 0; i < inliers; ++i) {
    const Point2 p{x(rng), y(rng)};
    const Point2 q = apply_homography(H, p);
    s.src.push_back(p);
    s.dst.push_back({q.x + jitter(rng), q.y + jitter(rng)});
  }
  for (int i = 0; i < outliers; ++i) {
    s.src.push_back({x(rng), y(rng)});
    s.dst.push_back({x(rng), y(rng)});
  }
  return s;
}

TEST(Homography, RecoversAKnownHomographyAmongOutliers) {
  const Homography truth = read_homography(test::sample_path("graf", "H1to2p"));
  for (int outliers : {0, 60, 150}) {
    const Synthetic s = synthetic(truth, 200, outliers, 0.5, 17);
    const HomographyResult result = find_homography_ransac(s.src, s.dst);
    ASSERT_TRUE(result.found) << result.failure;
    EXPECT_LT(mean_corner_error(result.H, truth, 800, 640), 0.5) << outliers << " outliers";
    EXPECT_GE(result.inliers, 195);
    EXPECT_LE(result.inliers, 200 + outliers / 10);
  }
}

TEST(Homography, SameAnswerForAnyOrderOfTheMatches) {
  const Homography truth = read_homography(test::sample_path("boat", "H1to2p"));
  const Synthetic s = synthetic(truth, 150, 120, 1.0, 23);
  const HomographyResult reference = find_homography_ransac(s.src, s.dst);
  std::mt19937 rng(5);
  std::vector<std::size_t> order(s.src.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(order.begin(), order.end(), rng);
    Synthetic shuffled;
    for (std::size_t i : order) {
      shuffled.src.push_back(s.src[i]);
      shuffled.dst.push_back(s.dst[i]);
    }
    const HomographyResult result = find_homography_ransac(shuffled.src, shuffled.dst);
    ASSERT_TRUE(result.found);
    EXPECT_EQ(result.H, reference.H) << "trial " << trial;
    EXPECT_EQ(result.inliers, reference.inliers);
    for (std::size_t k = 0; k < order.size(); ++k)
      ASSERT_EQ(result.inlier_mask[k], reference.inlier_mask[order[k]])
          << "trial " << trial << ", match " << k;
  }
}

TEST(Homography, DegenerateInputGetsNoModelAndAReason) {
  HomographyResult r = find_homography_ransac({{0, 0}, {1, 1}, {2, 5}}, {{0, 0}, {1, 1}, {2, 5}});
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.failure, "fewer than 4 matches");
  std::vector<Point2> line, line2;
  for (int i = 0; i < 30; ++i) {
    line.push_back({static_cast<double>(i), 2.0 * i});
    line2.push_back({static_cast<double>(i) + 3, 2.0 * i - 1});
  }
  r = find_homography_ransac(line, line2);
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.failure.find("collinear"), std::string::npos) << r.failure;
  std::vector<Point2> nan_points = {{0, 0}, {10, 0}, {0, 10}, {std::nan(""), 5}, {10, 10}};
  r = find_homography_ransac(nan_points, nan_points);
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.failure.find("non-finite"), std::string::npos);
  EXPECT_THROW(find_homography_ransac(line, nan_points), Error);
  RansacOptions bad;
  bad.confidence = 1.0;
  EXPECT_THROW(find_homography_ransac(line, line2, bad), Error);
}

TEST(Homography, AtLeastAsGoodAsOpenCvOnTheSamplePairs) {
  for (const char* sequence : {"graf", "boat", "leuven"}) {
    const cv::Mat a = test::load_sample_gray(sequence, "img1.png");
    const cv::Mat b = test::load_sample_gray(sequence, "img2.png");
    cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
    std::vector<cv::KeyPoint> ka, kb;
    cv::Mat da, db;
    orb->detectAndCompute(a, cv::noArray(), ka, da);
    orb->detectAndCompute(b, cv::noArray(), kb, db);
    const auto to_descriptors = [](const cv::Mat& m) {
      std::vector<Descriptor> out(static_cast<std::size_t>(m.rows));
      for (int r = 0; r < m.rows; ++r)
        std::copy_n(m.ptr<std::uint8_t>(r), 32, out[static_cast<std::size_t>(r)].begin());
      return out;
    };
    const std::vector<Match> matches = match_descriptors(to_descriptors(da), to_descriptors(db));
    std::vector<Point2> src, dst;
    std::vector<cv::Point2f> cv_src, cv_dst;
    for (const Match& m : matches) {
      const cv::Point2f p = ka[static_cast<std::size_t>(m.query)].pt,
                        q = kb[static_cast<std::size_t>(m.train)].pt;
      src.push_back({p.x, p.y});
      dst.push_back({q.x, q.y});
      cv_src.push_back(p);
      cv_dst.push_back(q);
    }
    const HomographyResult ours = find_homography_ransac(src, dst);
    const cv::Mat cv_h = cv::findHomography(cv_src, cv_dst, cv::RANSAC, 3.0);
    ASSERT_TRUE(ours.found) << sequence;
    ASSERT_FALSE(cv_h.empty()) << sequence;
    Homography theirs;
    for (int k = 0; k < 9; ++k) theirs[static_cast<std::size_t>(k)] = cv_h.at<double>(k / 3, k % 3);
    // OpenCV's returned mask is not a stable reference (docs/design.md §9): recount its model.
    int theirs_inliers = 0;
    for (std::size_t i = 0; i < src.size(); ++i) {
      const Point2 p = apply_homography(theirs, src[i]);
      if (std::hypot(p.x - dst[i].x, p.y - dst[i].y) <= 3.0) ++theirs_inliers;
    }
    EXPECT_GE(ours.inliers, theirs_inliers) << sequence;
    // Within 2 px of OpenCV's model, except as far as OpenCV's own model strays from the ground
    // truth (measured: graf 2.7 px off, ours 0.8 px), and never further from the truth than it.
    const Homography truth = read_homography(test::sample_path(sequence, "H1to2p"));
    const double ours_error = mean_corner_error(ours.H, truth, a.cols, a.rows);
    const double theirs_error = mean_corner_error(theirs, truth, a.cols, a.rows);
    EXPECT_LT(mean_corner_error(ours.H, theirs, a.cols, a.rows),
              2.0 + std::max(0.0, theirs_error - 1.0))
        << sequence;
    EXPECT_LE(ours_error, theirs_error + 0.25) << sequence;
    EXPECT_LT(ours_error, 1.5) << sequence;
    std::printf(
        "%s: %zu matches, ours %d inliers, OpenCV's model %d; corner error vs truth: ours %.2f, "
        "OpenCV %.2f\n",
        sequence, src.size(), ours.inliers, theirs_inliers, ours_error, theirs_error);
  }
}

}  // namespace
}  // namespace aief

// The OpenCV adapter and the ORB-SLAM2 drop-in give exactly the engine's features.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/opencv.hpp"
#include "aief/orbslam2_extractor.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

void expect_same(const Features& features, const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& descriptors) {
  ASSERT_EQ(keypoints.size(), features.keypoints.size());
  ASSERT_EQ(descriptors.rows, static_cast<int>(features.descriptors.size()));
  ASSERT_EQ(descriptors.cols, 32);
  ASSERT_EQ(descriptors.type(), CV_8U);
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    EXPECT_EQ(keypoints[i].pt.x, features.keypoints[i].x);
    EXPECT_EQ(keypoints[i].pt.y, features.keypoints[i].y);
    EXPECT_EQ(keypoints[i].angle, features.keypoints[i].angle_deg);
    EXPECT_EQ(keypoints[i].octave, features.keypoints[i].octave);
    EXPECT_EQ(keypoints[i].size, features.keypoints[i].size);
    ASSERT_EQ(0, std::memcmp(descriptors.ptr(static_cast<int>(i)), features.descriptors[i].data(), 32)) << "descriptor " << i;
  }
}

TEST(OpenCvAdapter, SameFeaturesAsTheEngineFromGrayOrColour) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  const Features features = extract(test::view_of(gray));
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv_extract(gray, keypoints, descriptors);
  expect_same(features, keypoints, descriptors);
  cv::Mat colour;
  cv::cvtColor(gray, colour, cv::COLOR_GRAY2BGR);
  CvExtractor extractor;
  extractor.detect_and_compute(colour, keypoints, descriptors);
  expect_same(features, keypoints, descriptors);
  EXPECT_THROW(cv_extract(cv::Mat(), keypoints, descriptors), Error);
  EXPECT_THROW(cv_extract(cv::Mat(100, 100, CV_32F), keypoints, descriptors), Error);
}

TEST(OpenCvAdapter, DescriptorsWorkWithOpenCvsMatcher) {
  const cv::Mat a = test::load_sample_gray("boat", "img1.png"), b = test::load_sample_gray("boat", "img2.png");
  std::vector<cv::KeyPoint> ka, kb;
  cv::Mat da, db;
  cv_extract(a, ka, da);
  cv_extract(b, kb, db);
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, true).match(da, db, matches);
  EXPECT_GT(matches.size(), 300u);
}

TEST(OrbSlam2DropIn, AccessorsAsOrbSlam2) {
  ORBextractor orb(1000, 1.2f, 8, 20, 7);
  EXPECT_EQ(orb.GetLevels(), 8);
  EXPECT_FLOAT_EQ(orb.GetScaleFactor(), 1.2f);
  const std::vector<float> scales = orb.GetScaleFactors(), sigma2 = orb.GetScaleSigmaSquares();
  ASSERT_EQ(scales.size(), 8u);
  float expected = 1.0f;
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(scales[static_cast<std::size_t>(i)], expected);
    EXPECT_EQ(sigma2[static_cast<std::size_t>(i)], expected * expected);
    EXPECT_EQ(orb.GetInverseScaleFactors()[static_cast<std::size_t>(i)], 1.0f / expected);
    EXPECT_EQ(orb.GetInverseScaleSigmaSquares()[static_cast<std::size_t>(i)], 1.0f / (expected * expected));
    expected *= 1.2f;
  }
}

TEST(OrbSlam2DropIn, CallOperatorGivesTheEnginesFeaturesAndPyramid) {
  const cv::Mat gray = test::load_sample_gray("leuven", "img1.png");
  ORBextractor orb(800, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb(gray, cv::Mat(), keypoints, descriptors);
  ExtractorOptions options;
  options.n_features = 800;
  expect_same(extract(test::view_of(gray), options), keypoints, descriptors);
  ASSERT_EQ(orb.mvImagePyramid.size(), 8u);
  EXPECT_EQ(cv::norm(orb.mvImagePyramid[0], gray, cv::NORM_INF), 0.0);
  EXPECT_EQ(orb.mvImagePyramid[1].cols, static_cast<int>(std::lround(gray.cols / 1.2f)));
}

TEST(OrbSlam2DropIn, ReadsItsSettingsKeys) {
  const std::string path = (std::filesystem::temp_directory_path() / "aief_orbslam2_settings.yaml").string();
  // Written as ORB-SLAM2's settings files are (OpenCV's writer refuses dotted keys; its reader takes them).
  std::ofstream(path) << "%YAML:1.0\n"
                      << "ORBextractor.nFeatures: 1500\nORBextractor.scaleFactor: 1.25\nORBextractor.nLevels: 6\n"
                      << "ORBextractor.iniThFAST: 25\nORBextractor.minThFAST: 9\nORBextractor.mode: \"quadtree-entropy\"\n"
                      << "ORBextractor.entropyThreshold: 3.5\nORBextractor.blockSize: 40\n";
  cv::FileStorage in(path, cv::FileStorage::READ);
  const ORBextractor orb = ORBextractor::from_settings(in);
  const ExtractorOptions& o = orb.extractor().options();
  EXPECT_EQ(o.n_features, 1500);
  EXPECT_DOUBLE_EQ(o.scale_factor, 1.25);
  EXPECT_EQ(o.n_levels, 6);
  EXPECT_EQ(o.fast_threshold, 25);
  EXPECT_EQ(o.fast_min_threshold, 9);
  EXPECT_EQ(o.distribution, Distribution::quadtree);
  EXPECT_EQ(o.entropy, EntropyMeasure::histogram);
  EXPECT_DOUBLE_EQ(o.entropy_threshold, 3.5);
  EXPECT_EQ(o.block_size, 40);
  EXPECT_EQ(orb.GetLevels(), 6);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace aief

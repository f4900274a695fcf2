// The OpenCV adapter gives exactly the engine's features, as cv::KeyPoint and CV_8U rows.
#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/feature2d.hpp"
#include "aief/opencv.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

cv::Mat read_homography(const std::string& path) {
  std::ifstream in(path);
  cv::Mat H(3, 3, CV_64F);
  for (int i = 0; i < 9; ++i) in >> H.at<double>(i / 3, i % 3);
  EXPECT_TRUE(in) << "cannot read 9 numbers from " << path;
  return H;
}

TEST(OpenCvAdapter, SameFeaturesAsTheEngineFromGrayBgrAndBgra) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  const Features features = extract(view_of(gray));
  ASSERT_GT(features.keypoints.size(), 500u);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv_extract(gray, keypoints, descriptors);
  EXPECT_TRUE(test::same_features(features, keypoints, descriptors));

  // Colour input is converted as cvtColor does; a gray image spread over the channels converts back
  // exactly.
  cv::Mat bgr, bgra;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(gray, bgra, cv::COLOR_GRAY2BGRA);
  CvExtractor extractor;
  extractor.detect_and_compute(bgr, keypoints, descriptors);
  EXPECT_TRUE(test::same_features(features, keypoints, descriptors));
  extractor.detect_and_compute(bgra, keypoints, descriptors);
  EXPECT_TRUE(test::same_features(features, keypoints, descriptors));
}

TEST(OpenCvAdapter, ColourIsConvertedAsCvtColor) {
  // A real colour image (channels differ): the adapter must equal the engine on cvtColor's gray.
  cv::Mat bgr(240, 320, CV_8UC3);
  cv::theRNG().state = 11;
  cv::randu(bgr, cv::Scalar::all(0), cv::Scalar::all(255));
  cv::GaussianBlur(bgr, bgr, cv::Size(5, 5), 1.5);
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  ExtractorOptions options;
  options.n_features = 400;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv_extract(bgr, keypoints, descriptors, options);
  ASSERT_GT(keypoints.size(), 100u);
  EXPECT_TRUE(test::same_features(extract(view_of(gray), options), keypoints, descriptors));
}

TEST(OpenCvAdapter, ReusesTheCallersStorageFrameAfterFrame) {
  // As cv::ORB: the outputs are written in place when the count is unchanged (so a shallow copy
  // of last frame's descriptors must be clone()d, as with OpenCV).
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  CvExtractor extractor;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  extractor.detect_and_compute(gray, keypoints, descriptors);
  const cv::KeyPoint* keypoint_storage = keypoints.data();
  const std::uint8_t* descriptor_storage = descriptors.data;
  extractor.detect_and_compute(gray, keypoints, descriptors);
  EXPECT_EQ(keypoints.data(), keypoint_storage);
  EXPECT_EQ(descriptors.data, descriptor_storage);
  EXPECT_TRUE(test::same_features(extract(view_of(gray)), keypoints, descriptors));
}

TEST(OpenCvAdapter, RegionOfInterestUsesItsStride) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  const cv::Mat roi = gray(cv::Rect(37, 21, 301, 257));  // not continuous: step != cols
  ASSERT_FALSE(roi.isContinuous());
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv_extract(roi, keypoints, descriptors);
  EXPECT_TRUE(test::same_features(extract(view_of(roi.clone())), keypoints, descriptors));
}

TEST(OpenCvAdapter, RefusesWhatItCannotRead) {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  EXPECT_THROW(cv_extract(cv::Mat(), keypoints, descriptors), Error);
  EXPECT_THROW(cv_extract(cv::Mat(100, 100, CV_32F, cv::Scalar(0)), keypoints, descriptors), Error);
  // The depth by its name, not its number (was "image depth 5"), in the adapter and Feature2D.
  for (const int type : {CV_32FC1, CV_16UC3}) {
    const cv::Mat image(100, 100, type, cv::Scalar(0));
    for (const auto& run : std::vector<std::function<void()>>{
             [&] { cv_extract(image, keypoints, descriptors); },
             [&] { opencv::Feature2D::create()->detect(image, keypoints); }}) {
      try {
        run();
        ADD_FAILURE() << "accepted";
      } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(type == CV_32FC1 ? "CV_32F" : "CV_16UC3"), std::string::npos)
            << message;
        EXPECT_EQ(message.find("depth 5"), std::string::npos) << message;
      }
    }
  }
  EXPECT_THROW(cv_extract(cv::Mat(100, 100, CV_8UC2, cv::Scalar(0)), keypoints, descriptors),
               Error);
  EXPECT_THROW(cv_extract(cv::Mat(10, 10, CV_8U, cv::Scalar(0)), keypoints, descriptors),
               Error);  // below the border
}

TEST(OpenCvAdapter, DescriptorsWorkWithOpenCvsMatcher) {
  const cv::Mat a = test::load_sample_gray("boat", "img1.png"),
                b = test::load_sample_gray("boat", "img2.png");
  std::vector<cv::KeyPoint> ka, kb;
  cv::Mat da, db;
  cv_extract(a, ka, da);
  cv_extract(b, kb, db);
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, true).match(da, db, matches);
  ASSERT_GT(matches.size(), 300u);
  // Usable, not just accepted: most of them agree with the sequence's ground-truth homography.
  const cv::Mat H = read_homography(test::sample_path("boat", "H1to2p"));
  int correct = 0;
  for (const cv::DMatch& m : matches) {
    const cv::Point2f p = ka[static_cast<std::size_t>(m.queryIdx)].pt,
                      q = kb[static_cast<std::size_t>(m.trainIdx)].pt;
    const double w = H.at<double>(2, 0) * p.x + H.at<double>(2, 1) * p.y + H.at<double>(2, 2);
    const double x = (H.at<double>(0, 0) * p.x + H.at<double>(0, 1) * p.y + H.at<double>(0, 2)) / w;
    const double y = (H.at<double>(1, 0) * p.x + H.at<double>(1, 1) * p.y + H.at<double>(1, 2)) / w;
    if (std::hypot(x - q.x, y - q.y) <= 3.0) ++correct;
  }
  EXPECT_GT(correct * 2, static_cast<int>(matches.size()))
      << correct << " of " << matches.size() << " matches within 3 px";
}

}  // namespace
}  // namespace aief

// aief::ORBextractor behaves as ORB-SLAM2's ORBextractor where ORB-SLAM2 reads it (call operator,
// settings keys) and computes exactly the engine's features. What both drop-ins share (accessors,
// constructor, pyramid) is tested once in tests/test_orbslam_dropins.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/orbslam2_extractor.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

TEST(OrbSlam2DropIn, CallOperatorGivesTheEnginesFeatures) {
  const cv::Mat gray = test::load_sample_gray("leuven", "img1.png");
  ORBextractor orb(800, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb(gray, cv::Mat(), keypoints, descriptors);
  // The same options: the drop-in's mode (orbslam2: no pool, ORB-SLAM's keypoint convention),
  // and ORB-SLAM2 passes a float.
  ExtractorOptions options = options_for_mode(ORBextractor::kDefaultMode);
  options.n_features = 800;
  options.scale_factor = 1.2f;
  const Features features = extract(view_of(gray), options);
  ASSERT_GT(features.keypoints.size(), 700u);
  EXPECT_TRUE(test::same_features(features, keypoints, descriptors));

  // Colour in, the same features out, after a frame of another size (the pyramid: in
  // tests/test_orbslam_dropins.cpp).
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  const cv::Mat small = test::load_sample_gray("boat", "img1.png")(cv::Rect(0, 0, 200, 150));
  orb(small, cv::noArray(), keypoints, descriptors);
  orb(bgr, cv::noArray(), keypoints, descriptors);
  EXPECT_TRUE(test::same_features(features, keypoints, descriptors));
}

TEST(OrbSlam2DropIn, MaskIsIgnoredAsOrbSlam2) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  ORBextractor orb(500, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> without_mask, with_mask;
  cv::Mat d_without, d_with;
  orb(gray, cv::noArray(), without_mask, d_without);
  orb(gray, cv::Mat::zeros(gray.size(), CV_8U), with_mask,
      d_with);  // a mask that would reject every pixel
  ASSERT_EQ(with_mask.size(), without_mask.size());
  EXPECT_EQ(cv::norm(d_with, d_without, cv::NORM_INF), 0.0);
}

TEST(OrbSlam2DropIn, NoKeypointReleasesTheDescriptorsAsOrbSlam2) {
  ORBextractor orb(500, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints(3);
  cv::Mat descriptors(3, 32, CV_8U, cv::Scalar(1));
  orb(cv::Mat(120, 160, CV_8U, cv::Scalar(128)), cv::noArray(), keypoints,
      descriptors);  // flat: no corner
  EXPECT_TRUE(keypoints.empty());
  EXPECT_TRUE(descriptors.empty());
  EXPECT_THROW(orb(cv::Mat(), cv::noArray(), keypoints, descriptors), Error);
  EXPECT_THROW(orb(cv::Mat(100, 100, CV_16U, cv::Scalar(0)), cv::noArray(), keypoints, descriptors),
               Error);
}

// Settings files written as ORB-SLAM2's are: OpenCV's writer refuses dotted keys, its reader takes
// them.
class SettingsFile {
 public:
  explicit SettingsFile(const std::string& body) : path_(folder_.file("settings.yaml")) {
    std::ofstream(path_) << "%YAML:1.0\n" << body;
  }
  cv::FileStorage open() const { return cv::FileStorage(path_, cv::FileStorage::READ); }

 private:
  test::TempFolder folder_{"aief_orbslam2"};
  std::string path_;
};

TEST(OrbSlam2DropIn, ReadsItsSettingsKeys) {
  const SettingsFile file(
      "ORBextractor.nFeatures: 1500\nORBextractor.scaleFactor: 1.3\nORBextractor.nLevels: 6\n"
      "ORBextractor.iniThFAST: 25\nORBextractor.minThFAST: 9\nORBextractor.mode: "
      "\"quadtree-entropy\"\n"
      "ORBextractor.entropyThreshold: 3.5\nORBextractor.blockSize: 40\n");
  const ORBextractor orb = ORBextractor::from_settings(file.open());
  const ExtractorOptions& o = orb.extractor().options();
  EXPECT_EQ(o.n_features, 1500);
  EXPECT_EQ(o.scale_factor, static_cast<double>(1.3f));  // read into a float, as Tracking.cc
  EXPECT_EQ(o.n_levels, 6);
  EXPECT_EQ(o.fast_threshold, 25);
  EXPECT_EQ(o.fast_min_threshold, 9);
  EXPECT_EQ(o.distribution, Distribution::quadtree);
  EXPECT_EQ(o.entropy, EntropyMeasure::histogram);
  EXPECT_EQ(o.entropy_threshold, 3.5);
  EXPECT_FALSE(o.auto_threshold);
  EXPECT_EQ(o.block_size, 40);
  EXPECT_TRUE(std::isinf(o.candidate_pool));  // a pool acts on the proportional distribution only
  EXPECT_EQ(orb.GetLevels(), 6);
  EXPECT_EQ(orb.GetScaleFactor(), 1.3f);
}

TEST(OrbSlam2DropIn, OrbSlam2sOwnSettingsGiveTheSameExtractorAsItsConstructor) {
  // RGB-D TUM1.yaml's values (a depth camera: the constructor's keypoint convention); Tracking.cc
  // reads scaleFactor into a float and calls the constructor.
  const SettingsFile file(
      "Camera.bf: 40.0\nThDepth: 40.0\nDepthMapFactor: 5000.0\n"
      "ORBextractor.nFeatures: 1000\nORBextractor.scaleFactor: 1.2\nORBextractor.nLevels: 8\n"
      "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n");
  ORBextractor from_file = ORBextractor::from_settings(file.open());
  ORBextractor from_numbers(1000, 1.2f, 8, 20, 7);
  EXPECT_EQ(from_file.GetScaleFactors(), from_numbers.GetScaleFactors());
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  std::vector<cv::KeyPoint> k1, k2;
  cv::Mat d1, d2;
  from_file(gray, cv::noArray(), k1, d1);
  from_numbers(gray, cv::noArray(), k2, d2);
  ASSERT_EQ(k1.size(), k2.size());
  for (std::size_t i = 0; i < k1.size(); ++i)
    ASSERT_TRUE(k1[i].pt == k2[i].pt && k1[i].octave == k2[i].octave) << "keypoint " << i;
  EXPECT_EQ(cv::norm(d1, d2, cv::NORM_INF), 0.0);
}

TEST(OrbSlam2DropIn, SettingsModesAndAutoThreshold) {
  {
    const SettingsFile file("ORBextractor.mode: \"orbslam2\"\n");
    const ExtractorOptions o = ORBextractor::options_from_settings(file.open());
    EXPECT_EQ(o.distribution, Distribution::quadtree);
    EXPECT_EQ(o.entropy, EntropyMeasure::off);
    EXPECT_EQ(o.n_features, ExtractorOptions{}.n_features);  // missing keys keep the defaults
  }
  {
    const SettingsFile file(
        "ORBextractor.mode: \"aief\"\nORBextractor.entropyThreshold: \"auto\"\n");
    const ExtractorOptions o = ORBextractor::options_from_settings(file.open());
    EXPECT_EQ(o.distribution, Distribution::proportional);
    EXPECT_TRUE(o.auto_threshold);
  }
  {
    // The mode keeps the drop-ins' conventions: a stereo rig's (Camera.bf) ...
    const SettingsFile file("Camera.bf: 47.9\nORBextractor.mode: \"aief\"\n");
    const ExtractorOptions o = ORBextractor::options_from_settings(file.open());
    EXPECT_EQ(o.coordinates, CoordinateMap::scaled);
    EXPECT_FALSE(o.subpixel);
    EXPECT_TRUE(std::isinf(o.candidate_pool));
  }
  {
    // ... and a monocular camera's.
    const SettingsFile file("ORBextractor.mode: \"aief\"\n");
    const ExtractorOptions o = ORBextractor::options_from_settings(file.open());
    EXPECT_EQ(o.coordinates, CoordinateMap::pixel_centre);
    EXPECT_TRUE(o.subpixel);
    EXPECT_TRUE(std::isinf(o.candidate_pool));
  }
  {
    // The engine's pool, if asked, where it acts (the proportional distribution); under this
    // drop-in's orbslam2 mode (the quadtree) it would do nothing, and is refused.
    const SettingsFile file("ORBextractor.mode: \"aief\"\nORBextractor.candidatePool: 1.25\n");
    EXPECT_EQ(ORBextractor::options_from_settings(file.open()).candidate_pool, 1.25);
    const SettingsFile quadtree("ORBextractor.candidatePool: 1.25\n");
    EXPECT_THROW(ORBextractor::options_from_settings(quadtree.open()), Error);
  }
  {
    const SettingsFile file(
        "ORBextractor.coordinates: \"pixel-centre\"\nORBextractor.subpixel: 1\n");
    const ExtractorOptions o = ORBextractor::options_from_settings(file.open());
    EXPECT_EQ(o.coordinates, CoordinateMap::pixel_centre);
    EXPECT_TRUE(o.subpixel);
  }
  {
    const SettingsFile file(
        "ORBextractor.candidatePool: \"off\"\n");  // docs/slam.md: spread, as the quadtree
    EXPECT_TRUE(std::isinf(ORBextractor::options_from_settings(file.open()).candidate_pool));
  }
}

TEST(OrbSlam2DropIn, SettingsErrorsNameTheKey) {
  const auto message_of = [](const std::string& body) -> std::string {
    const SettingsFile file(body);
    try {
      ORBextractor::from_settings(file.open());
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(message_of("ORBextractor.nFeatures: \"many\"\n").find("ORBextractor.nFeatures"),
            std::string::npos);
  EXPECT_NE(message_of("ORBextractor.nLevels: 7.5\n").find("ORBextractor.nLevels"),
            std::string::npos);
  EXPECT_NE(message_of("ORBextractor.scaleFactor: \"big\"\n").find("ORBextractor.scaleFactor"),
            std::string::npos);
  EXPECT_NE(
      message_of("ORBextractor.entropyThreshold: \"high\"\n").find("ORBextractor.entropyThreshold"),
      std::string::npos);
  EXPECT_NE(message_of("ORBextractor.mode: \"sift\"\n").find("sift"), std::string::npos);
  EXPECT_NE(message_of("ORBextractor.subpixel: 2\n").find("ORBextractor.subpixel"),
            std::string::npos);
  EXPECT_NE(message_of("ORBextractor.coordinates: \"centre\"\n").find("centre"), std::string::npos);
  EXPECT_NE(
      message_of("ORBextractor.candidatePool: 0.5\n").find("ORBextractor.candidatePool expects"),
      std::string::npos);
  EXPECT_NE(message_of("ORBextractor.scaleFactor: 0.5\n")
                .find("ORBextractor.scaleFactor expects a number in (1, 4]"),
            std::string::npos);
  EXPECT_NE(message_of("ORBextractor.scaleFactor: 1.00000001\n").find("scale_factor"),
            std::string::npos);  // validate()
  // A mode's conflicts are refused as in the CLI, named by the keys.
  EXPECT_NE(message_of("ORBextractor.mode: \"orbslam2\"\nORBextractor.entropyThreshold: 5\n")
                .find("ORBextractor.entropyThreshold sets F of the entropy mask, which "
                      "ORBextractor.mode orbslam2 turns off"),
            std::string::npos);
  EXPECT_THROW(ORBextractor::from_settings(cv::FileStorage()), Error);
}

}  // namespace
}  // namespace aief

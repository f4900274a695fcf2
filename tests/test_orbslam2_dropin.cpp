// aief::ORBextractor behaves as ORB-SLAM2's ORBextractor where ORB-SLAM2 reads it (accessors,
// call operator, settings keys) and computes exactly the engine's features.
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

void expect_same(const Features& features, const std::vector<cv::KeyPoint>& keypoints,
                 const cv::Mat& descriptors) {
  ASSERT_EQ(keypoints.size(), features.keypoints.size());
  ASSERT_EQ(descriptors.rows, static_cast<int>(features.descriptors.size()));
  ASSERT_EQ(descriptors.cols, kDescriptorBytes);
  ASSERT_EQ(descriptors.type(), CV_8U);
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const Keypoint& want = features.keypoints[i];
    const cv::KeyPoint& got = keypoints[i];
    ASSERT_TRUE(got.pt.x == want.x && got.pt.y == want.y && got.size == want.size &&
                got.angle == want.angle_deg && got.response == want.response &&
                got.octave == want.octave && got.class_id == -1)
        << "keypoint " << i << ": got (" << got.pt.x << ", " << got.pt.y << ") octave "
        << got.octave << " angle " << got.angle << ", want (" << want.x << ", " << want.y
        << ") octave " << want.octave << " angle " << want.angle_deg;
    for (int b = 0; b < kDescriptorBytes; ++b)
      ASSERT_EQ(descriptors.at<std::uint8_t>(static_cast<int>(i), b),
                features.descriptors[i][static_cast<std::size_t>(b)])
          << "descriptor " << i << " byte " << b;
  }
}

// The scale tables exactly as ORB-SLAM2's ORBextractor constructor computes them (float).
TEST(OrbSlam2DropIn, AccessorsAsOrbSlam2) {
  for (const float factor : {1.2f, 1.5f, 2.0f}) {
    for (const int levels : {1, 3, 8, 12}) {
      const ORBextractor orb(1000, factor, levels, 20, 7);
      EXPECT_EQ(orb.GetLevels(), levels);
      EXPECT_EQ(orb.GetScaleFactor(), factor);
      std::vector<float> scale(static_cast<std::size_t>(levels)),
          sigma2(static_cast<std::size_t>(levels));
      scale[0] = 1.0f;
      sigma2[0] = 1.0f;
      for (std::size_t i = 1; i < scale.size(); ++i) {
        scale[i] = scale[i - 1] * factor;
        sigma2[i] = scale[i] * scale[i];
      }
      ASSERT_EQ(orb.GetScaleFactors().size(), scale.size());
      ASSERT_EQ(orb.GetInverseScaleFactors().size(), scale.size());
      ASSERT_EQ(orb.GetScaleSigmaSquares().size(), scale.size());
      ASSERT_EQ(orb.GetInverseScaleSigmaSquares().size(), scale.size());
      for (std::size_t i = 0; i < scale.size(); ++i) {
        SCOPED_TRACE("factor " + std::to_string(factor) + ", level " + std::to_string(i));
        EXPECT_EQ(orb.GetScaleFactors()[i], scale[i]);
        EXPECT_EQ(orb.GetInverseScaleFactors()[i], 1.0f / scale[i]);
        EXPECT_EQ(orb.GetScaleSigmaSquares()[i], sigma2[i]);
        EXPECT_EQ(orb.GetInverseScaleSigmaSquares()[i], 1.0f / sigma2[i]);
      }
    }
  }
}

TEST(OrbSlam2DropIn, ConstructorArgumentsBecomeTheOptions) {
  const ORBextractor orb(1234, 1.3f, 6, 25, 9);
  const ExtractorOptions& o = orb.extractor().options();
  EXPECT_EQ(o.n_features, 1234);
  EXPECT_EQ(o.scale_factor, static_cast<double>(1.3f));
  EXPECT_EQ(o.n_levels, 6);
  EXPECT_EQ(o.fast_threshold, 25);
  EXPECT_EQ(o.fast_min_threshold, 9);
  // ORB-SLAM's choices unless the settings name a mode (docs/slam.md, "Which choice costs what")
  EXPECT_EQ(o.distribution, Distribution::quadtree);
  EXPECT_EQ(o.entropy, EntropyMeasure::off);
  EXPECT_EQ(o.coordinates,
            CoordinateMap::scaled);  // ORB-SLAM's keypoint convention (docs/slam.md, "Stereo")
  EXPECT_FALSE(o.subpixel);
  EXPECT_TRUE(std::isinf(o.candidate_pool));  // spread over the frame (docs/slam.md, "Results")
  EXPECT_THROW(ORBextractor(1000, 0.8f, 8, 20, 7), Error);
}

TEST(OrbSlam2DropIn, CallOperatorGivesTheEnginesFeaturesAndPyramid) {
  const cv::Mat gray = test::load_sample_gray("leuven", "img1.png");
  ORBextractor orb(800, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb(gray, cv::Mat(), keypoints, descriptors);
  // The same options: the drop-ins' mode (orbslam2: no pool, ORB-SLAM's keypoint convention),
  // and ORB-SLAM2 passes a float.
  ExtractorOptions options = options_for_mode(Mode::orbslam2);
  options.n_features = 800;
  options.scale_factor = 1.2f;
  const Features features = extract(view_of(gray), options);
  ASSERT_GT(features.keypoints.size(), 700u);
  expect_same(features, keypoints, descriptors);

  // The pyramid ORB-SLAM2's stereo matching reads: level 0 is the image, level n is
  // round(size / scale_n) as ORB-SLAM2 sizes it, and equals the engine's level.
  ASSERT_EQ(orb.mvImagePyramid.size(), 8u);
  EXPECT_EQ(cv::norm(orb.mvImagePyramid[0], gray, cv::NORM_INF), 0.0);
  for (int n = 1; n < 8; ++n) {
    const cv::Mat& level = orb.mvImagePyramid[static_cast<std::size_t>(n)];
    const float inverse = orb.GetInverseScaleFactors()[static_cast<std::size_t>(n)];
    EXPECT_EQ(level.cols, cvRound(static_cast<float>(gray.cols) * inverse)) << "level " << n;
    EXPECT_EQ(level.rows, cvRound(static_cast<float>(gray.rows) * inverse)) << "level " << n;
    const ImageView view = orb.extractor().pyramid_level(n);
    EXPECT_EQ(static_cast<const void*>(level.data), static_cast<const void*>(view.data))
        << "level " << n;
  }

  // Colour in, the same features out; the pyramid follows the latest frame.
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  const cv::Mat small = test::load_sample_gray("boat", "img1.png")(cv::Rect(0, 0, 200, 150));
  orb(small, cv::noArray(), keypoints, descriptors);
  EXPECT_EQ(orb.mvImagePyramid[0].cols, 200);
  orb(bgr, cv::noArray(), keypoints, descriptors);
  expect_same(features, keypoints, descriptors);
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
      "ORBextractor.entropyThreshold: 3.5\nORBextractor.blockSize: 40\nORBextractor.candidatePool: "
      "1.5\n");
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
  EXPECT_EQ(o.candidate_pool, 1.5);
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
    const SettingsFile file("ORBextractor.candidatePool: 1.25\n");  // the engine's pool, if asked
    EXPECT_EQ(ORBextractor::options_from_settings(file.open()).candidate_pool, 1.25);
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

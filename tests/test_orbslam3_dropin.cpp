// aief::orbslam3::ORBextractor behaves as ORB-SLAM3's ORBextractor where ORB-SLAM3 reads it
// (the call operator with its lapping area and returned count, settings keys) and
// computes exactly the engine's features. The settings parsing itself is shared with the
// ORB-SLAM2 drop-in and tested in depth there; what both drop-ins share (accessors, constructor,
// pyramid) is tested once in tests/test_orbslam_dropins.cpp.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/orbslam2_extractor.hpp"
#include "aief/orbslam3_extractor.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using orbslam3::ORBextractor;

// ORB-SLAM3's split, stated as positions: the keypoints outside [x0, x1] fill the front in the
// engine's order, those inside fill the back from the end (the first inside is last), and the
// returned count is the number outside.
void expect_lapping_split(const Features& features, int x0, int x1,
                          const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& descriptors,
                          int returned) {
  const std::size_t count = features.keypoints.size();
  ASSERT_EQ(keypoints.size(), count);
  ASSERT_EQ(descriptors.rows, static_cast<int>(count));
  ASSERT_EQ(descriptors.cols, kDescriptorBytes);
  ASSERT_EQ(descriptors.type(), CV_8U);
  std::size_t front = 0, back = count;
  for (std::size_t i = 0; i < count; ++i) {
    const float x = features.keypoints[i].x;
    const bool inside = x >= static_cast<float>(x0) && x <= static_cast<float>(x1);
    ASSERT_TRUE(
        test::same_keypoint_at(features, i, keypoints, descriptors, inside ? --back : front++));
  }
  EXPECT_EQ(returned, static_cast<int>(front)) << "lapping area [" << x0 << ", " << x1 << "]";
}

// The drop-in's options: its mode (faithful, docs/slam.md "Three seeds"), which also has
// ORB-SLAM's keypoint convention ("Stereo") and no pool ("Results").
ExtractorOptions options_of(int nfeatures, float scale_factor) {
  ExtractorOptions options = options_for_mode(ORBextractor::kDefaultMode);
  options.n_features = nfeatures;
  options.scale_factor = scale_factor;  // ORB-SLAM3 passes a float
  return options;
}

// Frame::ComputeStereoMatches centres its SAD window at round(x / scale) in mvImagePyramid and
// takes the disparity from x: every keypoint must sit at scale_n times a level pixel, or its
// disparity is off by the difference (docs/slam.md, "Stereo").
TEST(OrbSlam3DropIn, KeypointsSitOnTheLevelPixelsStereoMatchingReads) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  ORBextractor orb(1000, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  std::vector<int> stereo = {0, 0};
  orb(gray, cv::Mat(), keypoints, descriptors, stereo);
  ASSERT_GT(keypoints.size(), 900u);
  for (const cv::KeyPoint& kp : keypoints) {
    const float scale = orb.GetScaleFactors()[static_cast<std::size_t>(kp.octave)];
    const float inverse = orb.GetInverseScaleFactors()[static_cast<std::size_t>(kp.octave)];
    ASSERT_NEAR(kp.pt.x, scale * std::round(kp.pt.x * inverse), 1e-3f) << "octave " << kp.octave;
    ASSERT_NEAR(kp.pt.y, scale * std::round(kp.pt.y * inverse), 1e-3f) << "octave " << kp.octave;
  }
}

// Frame.cc's calls: stereo pinhole and RGB-D pass {0, 0}, monocular {0, 1000}, stereo fisheye the
// camera's overlap; other areas cover none, all, one column, and reversed bounds.
TEST(OrbSlam3DropIn, LappingAreaSplitAndReturnedCount) {
  const cv::Mat gray = test::load_sample_gray("leuven", "img1.png");  // 900 x 600
  // ORB-SLAM2 mode: level-0 keypoints lie on whole pixels, as ORB-SLAM3's, so a one-column area
  // can hold them.
  const ExtractorOptions options = options_for_mode(Mode::orbslam2, options_of(800, 1.2f));
  ORBextractor orb(options);
  const Features features = extract(view_of(gray), options);
  ASSERT_GT(features.keypoints.size(), 700u);
  const int x_of_first = static_cast<int>(features.keypoints.front().x);
  ASSERT_EQ(static_cast<float>(x_of_first), features.keypoints.front().x);
  const std::vector<std::vector<int>> areas = {{0, 0},
                                               {0, 1000},
                                               {300, 600},
                                               {-5, 5000},
                                               {600, 300},
                                               {x_of_first, x_of_first},
                                               {0, x_of_first - 1},
                                               {x_of_first + 1, 899}};
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (std::vector<int> area : areas) {
    SCOPED_TRACE("lapping area [" + std::to_string(area[0]) + ", " + std::to_string(area[1]) + "]");
    const int returned = orb(gray, cv::Mat(), keypoints, descriptors, area);
    expect_lapping_split(features, area[0], area[1], keypoints, descriptors, returned);
  }
  const int count = static_cast<int>(features.keypoints.size());

  // The cases spelled out. Nothing in {0, 0} (keypoints keep 19 pixels from the edge): the
  // engine's order, all counted, as ORB-SLAM2's drop-in gives them.
  std::vector<int> stereo_pinhole = {0, 0};
  EXPECT_EQ(orb(gray, cv::Mat(), keypoints, descriptors, stereo_pinhole), count);
  EXPECT_TRUE(test::same_keypoint_at(features, 0, keypoints, descriptors, 0));
  EXPECT_TRUE(test::same_keypoint_at(features, features.keypoints.size() - 1, keypoints,
                                     descriptors, features.keypoints.size() - 1));
  // Monocular frames pass {0, 1000}: on an image 1000 pixels wide or less every keypoint is
  // "in the area", so ORB-SLAM3 returns 0 and the order is reversed; Frame ignores both.
  std::vector<int> monocular = {0, 1000};
  EXPECT_EQ(orb(gray, cv::Mat(), keypoints, descriptors, monocular), 0);
  EXPECT_TRUE(
      test::same_keypoint_at(features, 0, keypoints, descriptors, features.keypoints.size() - 1));
  EXPECT_TRUE(
      test::same_keypoint_at(features, features.keypoints.size() - 1, keypoints, descriptors, 0));
  // The bounds are inclusive: [x, x] takes the keypoints on column x and nothing else.
  std::vector<int> one_column = {x_of_first, x_of_first};
  int on_column = 0;
  for (const Keypoint& kp : features.keypoints)
    on_column += kp.x == static_cast<float>(x_of_first) ? 1 : 0;
  ASSERT_GE(on_column, 1);
  EXPECT_EQ(orb(gray, cv::Mat(), keypoints, descriptors, one_column), count - on_column);
  // The first inside goes last.
  EXPECT_TRUE(
      test::same_keypoint_at(features, 0, keypoints, descriptors, features.keypoints.size() - 1));
  for (std::size_t slot = static_cast<std::size_t>(count - on_column); slot < keypoints.size();
       ++slot)
    EXPECT_EQ(keypoints[slot].pt.x, static_cast<float>(x_of_first)) << "slot " << slot;
  // Reversed bounds hold nothing.
  std::vector<int> reversed = {600, 300};
  EXPECT_EQ(orb(gray, cv::Mat(), keypoints, descriptors, reversed), count);
}

// Keypoints of coarse levels have fractional x: the int bounds compare as float, as in ORB-SLAM3.
TEST(OrbSlam3DropIn, FractionalXAgainstIntegerBounds) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  const Features features = extract(view_of(gray), options_of(1000, 1.2f));
  const Keypoint* fractional = nullptr;
  for (const Keypoint& kp : features.keypoints)
    if (kp.x != static_cast<float>(static_cast<int>(kp.x))) fractional = &kp;
  ASSERT_NE(fractional, nullptr) << "no keypoint with a fractional x";
  const int below = static_cast<int>(fractional->x);  // x lies strictly between below and below + 1
  ORBextractor orb(1000, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (std::vector<int> area :
       std::vector<std::vector<int>>{{below, below}, {below + 1, below + 1}, {below, below + 1}}) {
    SCOPED_TRACE("lapping area [" + std::to_string(area[0]) + ", " + std::to_string(area[1]) + "]");
    const int returned = orb(gray, cv::noArray(), keypoints, descriptors, area);
    expect_lapping_split(features, area[0], area[1], keypoints, descriptors, returned);
    const bool holds_fractional = area[0] == below && area[1] == below + 1;
    bool found_in_back = false;
    for (std::size_t slot = static_cast<std::size_t>(returned); slot < keypoints.size(); ++slot)
      found_in_back = found_in_back || (keypoints[slot].pt.x == fractional->x &&
                                        keypoints[slot].pt.y == fractional->y);
    EXPECT_EQ(found_in_back, holds_fractional);
  }
}

TEST(OrbSlam3DropIn, ColourAndMaskAsOrbSlam3) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  ORBextractor orb(500, 1.2f, 8, 20, 7);
  std::vector<int> area = {0, 0};
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb(gray, cv::Mat::zeros(gray.size(), CV_8U), keypoints, descriptors,
      area);  // a mask that would reject every pixel
  const Features features = extract(view_of(gray), options_of(500, 1.2f));
  expect_lapping_split(features, 0, 0, keypoints, descriptors, static_cast<int>(keypoints.size()));

  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  const int returned = orb(bgr, cv::noArray(), keypoints, descriptors, area);
  expect_lapping_split(features, 0, 0, keypoints, descriptors, returned);
}

TEST(OrbSlam3DropIn, EmptyImageReturnsMinusOneAndOtherBadInputThrows) {
  ORBextractor orb(500, 1.2f, 8, 20, 7);
  std::vector<int> area = {0, 0};
  std::vector<cv::KeyPoint> keypoints(3);
  cv::Mat descriptors(3, 32, CV_8U, cv::Scalar(1));
  EXPECT_EQ(orb(cv::Mat(), cv::noArray(), keypoints, descriptors, area), -1);  // ORB-SLAM3's answer
  EXPECT_EQ(keypoints.size(), 3u);  // outputs untouched, as ORB-SLAM3
  EXPECT_EQ(descriptors.rows, 3);
  EXPECT_TRUE(orb.mvImagePyramid.empty());

  // A flat image has no corner: no keypoint, descriptors released, count 0.
  EXPECT_EQ(
      orb(cv::Mat(120, 160, CV_8U, cv::Scalar(128)), cv::noArray(), keypoints, descriptors, area),
      0);
  EXPECT_TRUE(keypoints.empty());
  EXPECT_TRUE(descriptors.empty());

  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  std::vector<int> one_bound = {0};
  EXPECT_THROW(orb(gray, cv::noArray(), keypoints, descriptors, one_bound), Error);
  EXPECT_THROW(
      orb(cv::Mat(100, 100, CV_16U, cv::Scalar(0)), cv::noArray(), keypoints, descriptors, area),
      Error);
  EXPECT_THROW(
      orb(cv::Mat(30, 300, CV_8U, cv::Scalar(0)), cv::noArray(), keypoints, descriptors, area),
      Error);  // too small
}

TEST(OrbSlam3DropIn, OrbSlam3sOwnSettingsGiveTheSameExtractorAsItsConstructor) {
  // EuRoC.yaml's ORB values, a stereo rig (the constructor's keypoint convention); Tracking.cc
  // reads scaleFactor into a float and calls the constructor.
  const cv::FileStorage settings(
      "%YAML:1.0\nStereo.b: 0.0745\nORBextractor.nFeatures: 1200\nORBextractor.scaleFactor: "
      "1.2\nORBextractor.nLevels: 8\n"
      "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n",
      cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ORBextractor from_file = ORBextractor::from_settings(settings);
  ORBextractor from_numbers(1200, 1.2f, 8, 20, 7);
  EXPECT_EQ(from_file.GetScaleFactors(), from_numbers.GetScaleFactors());
  EXPECT_EQ(from_file.extractor().options().n_features, 1200);
  const cv::Mat gray = test::load_sample_gray("boat", "img2.png");
  std::vector<int> area = {200, 500};
  std::vector<cv::KeyPoint> k1, k2;
  cv::Mat d1, d2;
  const int mono1 = from_file(gray, cv::noArray(), k1, d1, area);
  const int mono2 = from_numbers(gray, cv::noArray(), k2, d2, area);
  EXPECT_EQ(mono1, mono2);
  ASSERT_EQ(k1.size(), k2.size());
  for (std::size_t i = 0; i < k1.size(); ++i)
    ASSERT_TRUE(k1[i].pt == k2[i].pt && k1[i].octave == k2[i].octave) << "keypoint " << i;
  EXPECT_EQ(cv::norm(d1, d2, cv::NORM_INF), 0.0);

  // Our keys too (threads: docs/orbslam3.md's advice for 2-core boards), and a wrong value names
  // its key.
  const cv::FileStorage ours(
      "%YAML:1.0\nORBextractor.mode: \"orbslam2\"\nORBextractor.threads: 1\n",
      cv::FileStorage::READ | cv::FileStorage::MEMORY);
  const ExtractorOptions ours_options = ORBextractor::from_settings(ours).extractor().options();
  EXPECT_EQ(ours_options.distribution, Distribution::quadtree);
  EXPECT_EQ(ours_options.threads, 1);
  EXPECT_EQ(ORBextractor::options_from_settings(settings).threads,
            ExtractorOptions{}.threads);  // missing: the default
  // No mode named: the faithful mode (ORB-SLAM3's own pyramid, cells, ties and angles); the
  // ORB-SLAM2 drop-in keeps orbslam2 mode.
  const ExtractorOptions unnamed = ORBextractor::options_from_settings(settings);
  const ExtractorOptions faithful = options_for_mode(Mode::faithful);
  EXPECT_EQ(unnamed.pyramid_resampling, faithful.pyramid_resampling);
  EXPECT_EQ(unnamed.detection_cells, faithful.detection_cells);
  EXPECT_EQ(unnamed.quadtree_ties, faithful.quadtree_ties);
  EXPECT_EQ(unnamed.orientation, faithful.orientation);
  EXPECT_EQ(aief::ORBextractor::options_from_settings(settings).pyramid_resampling,
            options_for_mode(Mode::orbslam2).pyramid_resampling);
  EXPECT_NE(faithful.pyramid_resampling, options_for_mode(Mode::orbslam2).pyramid_resampling);
  const cv::FileStorage negative("%YAML:1.0\nORBextractor.threads: -1\n",
                                 cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_THROW(ORBextractor::from_settings(negative), Error);
  const cv::FileStorage wrong("%YAML:1.0\nORBextractor.nLevels: 7.5\n",
                              cv::FileStorage::READ | cv::FileStorage::MEMORY);
  try {
    ORBextractor::from_settings(wrong);
    ADD_FAILURE() << "nLevels 7.5 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ORBextractor.nLevels"), std::string::npos) << e.what();
  }
}

// Settings that describe a stereo rig or a depth camera (either settings format) get ORB-SLAM's
// integer level pixels, which Frame::ComputeStereoMatches needs; monocular settings the engine's
// pixel-centre, sub-pixel keypoints (docs/slam.md, "The keypoint convention in monocular").
std::string settings_error(const std::string& body) {
  try {
    ORBextractor::options_from_settings(
        cv::FileStorage("%YAML:1.0\n" + body, cv::FileStorage::READ | cv::FileStorage::MEMORY));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A misspelt ORBextractor key was ignored (ORBextractor.entropyTreshold: 2.5 and
// ORBextractor.nFeature: 300 ran with F = 4 and 1000 features), and fastThresholdFrom, which
// docs/slam.md recommends, did nothing under this drop-in's default (faithful: ORB-SLAM's cells).
TEST(OrbSlam3DropIn, MisspeltKeysAndSettingsThatCannotActAreRefused) {
  EXPECT_NE(settings_error("ORBextractor.mode: \"aief\"\nORBextractor.entropyTreshold: 2.5\n")
                .find("unknown setting 'ORBextractor.entropyTreshold' (did you mean "
                      "ORBextractor.entropyThreshold?)"),
            std::string::npos);
  EXPECT_NE(
      settings_error("ORBextractor.nFeature: 300\n").find("(did you mean ORBextractor.nFeatures?)"),
      std::string::npos);
  // The prefix in another case was skipped as another section's key: nFeatures 300 ran with 1000.
  for (const std::string prefix : {"ORBExtractor.", "orbextractor."})
    EXPECT_NE(settings_error(prefix + "nFeatures: 300\n")
                  .find("unknown setting '" + prefix +
                        "nFeatures': ORB-SLAM's extractor keys begin with 'ORBextractor.', in "
                        "this case exactly (did you mean ORBextractor.nFeatures?)"),
              std::string::npos)
        << prefix;
  EXPECT_NE(settings_error("ORBextractor.fastThresholdFrom: \"entropy\"\n")
                .find("ORBextractor.fastThresholdFrom entropy does nothing unless "
                      "ORBextractor.detectionCells blocks"),
            std::string::npos);
  // With the engine's blocks it acts (docs/slam.md's fto: orbslam2 mode), and ORB-SLAM's own keys
  // and other sections' keys are read as before.
  EXPECT_EQ(settings_error("ORBextractor.mode: \"orbslam2\"\n"
                           "ORBextractor.fastThresholdFrom: \"entropy\"\n"),
            "");
  EXPECT_EQ(settings_error("ORBextractor.detectionCells: \"blocks\"\n"
                           "ORBextractor.fastThresholdFrom: \"entropy\"\n"),
            "");
  // Values as written, or what OpenCV's reader made of them (was: 2147483648 shown as
  // -2147483648, 2^32 as 0, an empty value as "...", .nan as "-nan").
  EXPECT_NE(settings_error("ORBextractor.nFeatures: 2147483648\n")
                .find("as OpenCV's settings reader reads it (it keeps integers in 32 bits"),
            std::string::npos);
  EXPECT_NE(settings_error("ORBextractor.nFeatures: 4294967296\n").find("got 0 as OpenCV's"),
            std::string::npos);
  EXPECT_NE(settings_error("ORBextractor.nFeatures:\n").find("ORBextractor.nFeatures has no value"),
            std::string::npos);
  EXPECT_NE(settings_error("ORBextractor.scaleFactor: .nan\n").find("got '.nan'"),
            std::string::npos);
  EXPECT_EQ(settings_error("ORBextractor.scaleFactor: .nan\n").find("-nan"), std::string::npos);
  EXPECT_EQ(settings_error("Camera.fx: 500.0\nORBextractor.nFeatures: 1200\n"
                           "ORBextractor.scaleFactor: 1.2\nORBextractor.nLevels: 8\n"
                           "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n"),
            "");
}

TEST(OrbSlam3DropIn, KeypointConventionFollowsTheSensorTheSettingsDescribe) {
  const auto options_of_settings = [](const std::string& body) {
    return ORBextractor::options_from_settings(
        cv::FileStorage("%YAML:1.0\n" + body, cv::FileStorage::READ | cv::FileStorage::MEMORY));
  };
  for (const std::string key :
       {"Camera.bf: 47.9", "ThDepth: 35.0", "DepthMapFactor: 5000.0", "Camera2.fx: 458.654",
        "Stereo.b: 0.0745", "Stereo.ThDepth: 60.0", "RGBD.DepthMapFactor: 5000.0"}) {
    const ExtractorOptions o = options_of_settings("Camera1.fx: 458.654\n" + key + "\n");
    EXPECT_EQ(o.coordinates, CoordinateMap::scaled) << key;
    EXPECT_FALSE(o.subpixel) << key;
  }
  const std::string monocular = "Camera.type: \"PinHole\"\nCamera1.fx: 458.654\n";
  const ExtractorOptions mono = options_of_settings(monocular);
  EXPECT_EQ(mono.coordinates, CoordinateMap::pixel_centre);
  EXPECT_TRUE(mono.subpixel);
  EXPECT_TRUE(std::isinf(mono.candidate_pool));
  // Keys given win over either convention.
  const ExtractorOptions asked = options_of_settings(
      monocular + "ORBextractor.coordinates: \"scaled\"\nORBextractor.subpixel: 0\n");
  EXPECT_EQ(asked.coordinates, CoordinateMap::scaled);
  EXPECT_FALSE(asked.subpixel);
}

TEST(OrbSlam3DropIn, CarriedThresholdFromTheSettingsChangesFAfterTheFirstSweep) {
  const cv::FileStorage settings(
      "%YAML:1.0\nORBextractor.mode: \"aief\"\nORBextractor.nFeatures: 500\n"
      "ORBextractor.entropyThreshold: \"carried\"\n"
      "ORBextractor.carryEvery: 15\n",
      cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ORBextractor orb = ORBextractor::from_settings(settings);
  EXPECT_TRUE(orb.extractor().options().carried_threshold);
  EXPECT_EQ(orb.extractor().options().carry_every, 15);
  // A panning, dimming video: F starts at the default and the first sweep's F replaces it (the
  // sweep is spread over the frames, core/sweep/spread_sweep.hpp: at 320x240 and 500 features it
  // completes within 90 frames).
  const cv::Mat scene = test::load_sample_gray("leuven", "img1.png");
  std::vector<double> used;
  std::vector<int> area = {0, 0};
  for (int t = 0; t < 90; ++t) {
    cv::Mat frame;
    scene(cv::Rect(100 + 3 * t, 80 + t, 320, 240)).convertTo(frame, CV_8U, 1.0, -1.0 * t);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb(frame, cv::noArray(), keypoints, descriptors, area);
    used.push_back(orb.last_frame_info().entropy_threshold_requested);
  }
  EXPECT_EQ(used.front(), ExtractorOptions{}.entropy_threshold);
  EXPECT_NE(used.back(), used.front()) << "the first sweep ends within 90 frames";

  const cv::FileStorage zero("%YAML:1.0\nORBextractor.carryEvery: 0\n",
                             cv::FileStorage::READ | cv::FileStorage::MEMORY);
  try {
    ORBextractor::from_settings(zero);
    ADD_FAILURE() << "carryEvery 0 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ORBextractor.carryEvery"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aief

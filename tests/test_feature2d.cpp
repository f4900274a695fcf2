// aief::opencv::Feature2D: a cv::Feature2D bit-exact with the engine; compute() for given keypoints
// (Extractor::describe) and its rules: level from the octave, border rule, angle recomputed.
#include <cmath>
#include <cstring>
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

// "" when both hold the same keypoints (every field, bit for bit) and descriptor bytes.
std::string first_difference(const std::vector<cv::KeyPoint>& a, const cv::Mat& da,
                             const std::vector<cv::KeyPoint>& b, const cv::Mat& db) {
  if (a.size() != b.size())
    return std::to_string(a.size()) + " keypoints vs " + std::to_string(b.size());
  if (da.rows != db.rows || da.cols != db.cols || da.type() != db.type())
    return "descriptor matrices differ in shape";
  for (std::size_t i = 0; i < a.size(); ++i) {
    const cv::KeyPoint &p = a[i], &q = b[i];
    if (std::memcmp(&p.pt, &q.pt, sizeof p.pt) != 0 ||
        std::memcmp(&p.size, &q.size, sizeof(float)) != 0 ||
        std::memcmp(&p.angle, &q.angle, sizeof(float)) != 0 ||
        std::memcmp(&p.response, &q.response, sizeof(float)) != 0 || p.octave != q.octave ||
        p.class_id != q.class_id)
      return "keypoint " + std::to_string(i) + ": (" + std::to_string(p.pt.x) + ", " +
             std::to_string(p.pt.y) + ", angle " + std::to_string(p.angle) + ") vs (" +
             std::to_string(q.pt.x) + ", " + std::to_string(q.pt.y) + ", angle " +
             std::to_string(q.angle) + ")";
    if (!da.empty() && std::memcmp(da.ptr(static_cast<int>(i)), db.ptr(static_cast<int>(i)),
                                   static_cast<std::size_t>(da.cols)) != 0)
      return "descriptor " + std::to_string(i);
  }
  return "";
}

constexpr Mode kEveryMode[] = {Mode::aief, Mode::aief_paper, Mode::orbslam2,
                               Mode::quadtree_entropy};

TEST(Feature2D, IsACvFeature2DWithOrbsDescriptorShape) {
  const cv::Ptr<cv::Feature2D> detector = opencv::Feature2D::create();
  EXPECT_EQ(detector->descriptorSize(), 32);
  EXPECT_EQ(detector->descriptorType(), CV_8U);
  EXPECT_EQ(detector->defaultNorm(), cv::NORM_HAMMING);
  EXPECT_EQ(detector->getDefaultName(), "Feature2D.AIEF");
  EXPECT_FALSE(detector->empty());
}

TEST(Feature2D, OptionsGoThroughFileStorage) {
  ExtractorOptions options = options_for_mode(Mode::orbslam2);
  options.n_features = 777;
  options.scale_factor = 1.3;
  const cv::Ptr<cv::Feature2D> written = opencv::Feature2D::create(options);
  cv::FileStorage out("settings.yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  written->write(out);
  const cv::String text = out.releaseAndGetString();
  cv::FileStorage in(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  const cv::Ptr<opencv::Feature2D> read = opencv::Feature2D::create();
  read->read(in.root());
  EXPECT_EQ(read->options().n_features, 777);
  EXPECT_EQ(read->options().scale_factor, 1.3);
  EXPECT_EQ(read->options().distribution, options.distribution);
  EXPECT_EQ(read->options().entropy, options.entropy);
  EXPECT_EQ(read->options().coordinates, options.coordinates);
  cv::FileStorage bad("%YAML:1.0\nn_features: -5\n",
                      cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_THROW(read->read(bad.root()), Error);
  EXPECT_EQ(read->options().n_features, 777) << "a bad setting leaves the detector as it was";
}

// read() refuses a key it would not read, naming it: a typo, cv::ORB's own settings (what
// cv::ORB::write writes), leaving the detector as it was. Was: ignored without a word.
TEST(Feature2D, ReadRefusesKeysItDoesNotReadNamingThem) {
  const cv::Ptr<opencv::Feature2D> detector = opencv::Feature2D::create();
  const auto message_of = [&](const std::string& yaml) {
    cv::FileStorage in("%YAML:1.0\n" + yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    try {
      detector->read(in.root());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message_of("n_features: 500\nn_featres: 300\n").find("unknown key 'n_featres'"),
            std::string::npos);
  EXPECT_NE(message_of("nfeatures: 300\n").find("'nfeatures' is cv::ORB's setting"),
            std::string::npos);
  EXPECT_NE(message_of("nfeatures: 300\n").find("n_features"), std::string::npos);
  EXPECT_EQ(detector->options().n_features, ExtractorOptions{}.n_features) << "left as it was";
  // What cv::ORB::write writes in the OpenCV versions that write its settings.
  EXPECT_NE(message_of("name: Feature2D.ORB\nnfeatures: 500\nscaleFactor: 1.2\nnlevels: 8\n"
                       "edgeThreshold: 31\nfirstLevel: 0\nwta_k: 2\nscoreType: 0\n"
                       "patchSize: 31\nfastThreshold: 20\n")
                .find("cv::ORB's setting"),
            std::string::npos);
  EXPECT_EQ(message_of("name: Feature2D.AIEF\nn_features: 500\n"), "no error");
  EXPECT_EQ(detector->options().n_features, 500);
  // The nearest key is named (as the ORB-SLAM settings reader names it).
  EXPECT_NE(message_of("n_featres: 300\n").find("(did you mean n_features?)"), std::string::npos);
}

// An option that cannot act with the others is refused however the detector is made: from options
// (validate(), core/options/acts_with.hpp) or by read(). Was: faithful with the per-block FAST
// thresholds from entropy gave faithful's keypoints.
TEST(Feature2D, AnOptionThatCannotActIsRefused) {
  ExtractorOptions faithful = options_for_mode(Mode::faithful);
  faithful.fast_threshold_from = FastThresholdFrom::entropy;
  try {
    opencv::Feature2D::create(faithful);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "fast_threshold_from entropy does nothing unless detection_cells blocks"),
              std::string::npos)
        << e.what();
  }
  const cv::Ptr<opencv::Feature2D> detector = opencv::Feature2D::create();
  cv::FileStorage in("%YAML:1.0\nquadtree_weight: entropy\n",
                     cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_THROW(detector->read(in.root()), Error);  // the default distribution is proportional
  EXPECT_EQ(detector->options().quadtree_weight, QuadtreeWeight::none) << "left as it was";
}

TEST(Feature2D, DetectAndComputeGivesTheEnginesFeatures) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  for (Mode mode : kEveryMode) {
    const ExtractorOptions options = options_for_mode(mode);
    std::vector<cv::KeyPoint> keypoints, expected_keypoints;
    cv::Mat descriptors, expected_descriptors;
    opencv::Feature2D::create(options)->detectAndCompute(gray, cv::noArray(), keypoints,
                                                         descriptors);
    cv_extract(gray, expected_keypoints, expected_descriptors, options);
    ASSERT_GT(keypoints.size(), 500u);
    EXPECT_EQ(first_difference(keypoints, descriptors, expected_keypoints, expected_descriptors),
              "")
        << to_string(mode);
  }
}

// The contract users of cv::Feature2D rely on: detect, then compute, is detectAndCompute.
TEST(Feature2D, DetectThenComputeIsDetectAndComputeBitForBit) {
  for (const char* sequence : {"graf", "boat", "leuven"}) {
    const cv::Mat gray = test::load_sample_gray(sequence, "img1.png");
    for (Mode mode : kEveryMode) {
      const cv::Ptr<cv::Feature2D> detector = opencv::Feature2D::create(options_for_mode(mode));
      std::vector<cv::KeyPoint> both, separate;
      cv::Mat both_descriptors, separate_descriptors;
      detector->detectAndCompute(gray, cv::noArray(), both, both_descriptors);
      detector->detect(gray, separate);
      const std::size_t detected = separate.size();
      detector->compute(gray, separate, separate_descriptors);
      EXPECT_EQ(separate.size(), detected) << "compute removed detected keypoints";
      EXPECT_EQ(first_difference(both, both_descriptors, separate, separate_descriptors), "")
          << sequence << " " << to_string(mode);
    }
  }
}

TEST(Feature2D, TheMaskIsTheEnginesDetectionMask) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  cv::Mat mask(gray.size(), CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(0, 0, gray.cols / 2, gray.rows)).setTo(255);
  std::vector<cv::KeyPoint> keypoints, detected;
  cv::Mat descriptors;
  const cv::Ptr<cv::Feature2D> detector = opencv::Feature2D::create();
  detector->detectAndCompute(gray, mask, keypoints, descriptors);
  detector->detect(gray, detected, mask);
  Features expected;
  Extractor().extract(view_of(gray), view_of(mask), expected);
  EXPECT_EQ(first_difference(keypoints, descriptors, to_cv_keypoints(expected),
                             to_cv_descriptors(expected)),
            "");
  EXPECT_EQ(keypoints.size(), 1000u);
  EXPECT_EQ(first_difference(keypoints, cv::Mat(), detected, cv::Mat()), "");
  EXPECT_THROW(detector->detect(gray, detected, cv::Mat(gray.size(), CV_32F, cv::Scalar(1))),
               Error);
}

TEST(Feature2D, ComputeKeepsEachKeypointsFieldsAndRemovesThoseNearTheEdge) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  const int w = gray.cols, h = gray.rows;
  // Level 0 of the default mode maps x to the pixel round(x): 19 is the first pixel kept.
  std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(100.f, 100.f, 7.f, 42.f, 3.f, 0, 11),
                                         cv::KeyPoint(18.4f, 200.f, 31.f, -1.f, 0.f, 0, 12),
                                         cv::KeyPoint(18.6f, 200.f, 31.f, -1.f, 0.f, 0, 13),
                                         cv::KeyPoint(w - 19.6f, 200.f, 31.f, -1.f, 0.f, 0, 14),
                                         cv::KeyPoint(w - 19.4f, 200.f, 31.f, -1.f, 0.f, 0, 15),
                                         cv::KeyPoint(300.f, h - 19.6f, 31.f, -1.f, 0.f, 0, 16),
                                         cv::KeyPoint(300.f, h - 19.4f, 31.f, -1.f, 0.f, 0, 17),
                                         cv::KeyPoint(300.f, 300.f, 31.f, -1.f, 0.f, 3, 18)};
  const std::vector<cv::KeyPoint> given = keypoints;
  cv::Mat descriptors;
  opencv::Feature2D::create()->compute(gray, keypoints, descriptors);
  ASSERT_EQ(keypoints.size(), 5u);
  const int expected_ids[] = {11, 13, 14, 16, 18};
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    EXPECT_EQ(keypoints[k].class_id, expected_ids[k]);
    const cv::KeyPoint& original = given[static_cast<std::size_t>(expected_ids[k] - 11)];
    EXPECT_EQ(keypoints[k].pt, original.pt);
    EXPECT_EQ(keypoints[k].size, original.size);
    EXPECT_EQ(keypoints[k].response, original.response);
    EXPECT_EQ(keypoints[k].octave, original.octave);
    EXPECT_EQ(keypoints[k].angle, original.angle);  // -1 (OpenCV's "no angle") too, as cv::ORB
  }
  EXPECT_EQ(descriptors.rows, 5);
  EXPECT_EQ(descriptors.type(), CV_8U);
}

// compute() keeps the angles it is given, as cv::ORB::compute does: graf's keypoints carried to
// the image turned by 30 degrees, with their true angles, come back with those angles (and so
// with the descriptors of the true orientation). GivenAngles::recompute re-estimates them on the
// turned, re-interpolated image. Was: recomputed by default.
TEST(Feature2D, ComputeKeepsTheGivenAnglesAsCvOrb) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  constexpr double kTurnDeg = 30;
  const cv::Mat rotation =
      cv::getRotationMatrix2D(cv::Point2f(gray.cols / 2.f, gray.rows / 2.f), kTurnDeg, 1.0);
  cv::Mat turned;
  cv::warpAffine(gray, turned, rotation, gray.size());
  std::vector<cv::KeyPoint> detected;
  opencv::Feature2D::create()->detect(gray, detected);
  std::vector<cv::KeyPoint> moved;
  for (const cv::KeyPoint& kp : detected) {
    const cv::Matx23d m = rotation;
    const cv::Point2f p(static_cast<float>(m(0, 0) * kp.pt.x + m(0, 1) * kp.pt.y + m(0, 2)),
                        static_cast<float>(m(1, 0) * kp.pt.x + m(1, 1) * kp.pt.y + m(1, 2)));
    // The image turns counter-clockwise (y down): an orientation theta becomes theta - 30.
    const float angle = static_cast<float>(std::fmod(kp.angle - kTurnDeg + 360.0, 360.0));
    moved.emplace_back(p, kp.size, angle, kp.response, kp.octave, static_cast<int>(moved.size()));
  }
  std::vector<cv::KeyPoint> kept = moved, recomputed = moved;
  cv::Mat descriptors, recomputed_descriptors;
  opencv::Feature2D::create()->compute(turned, kept, descriptors);
  opencv::Feature2D::create({}, GivenAngles::recompute)
      ->compute(turned, recomputed, recomputed_descriptors);
  ASSERT_GT(kept.size(), moved.size() * 3 / 4);
  ASSERT_EQ(kept.size(), recomputed.size());
  int angles_moved = 0;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    EXPECT_EQ(kept[k].angle, moved[static_cast<std::size_t>(kept[k].class_id)].angle);
    angles_moved += recomputed[k].angle != kept[k].angle ? 1 : 0;
  }
  EXPECT_GT(angles_moved, static_cast<int>(kept.size()) / 2) << "recompute re-estimates them";
  // cv::ORB, given the same keypoints, keeps the same angles.
  std::vector<cv::KeyPoint> orb_kept = moved;
  cv::Mat orb_descriptors;
  cv::ORB::create()->compute(turned, orb_kept, orb_descriptors);
  for (const cv::KeyPoint& kp : orb_kept)
    EXPECT_EQ(kp.angle, moved[static_cast<std::size_t>(kp.class_id)].angle);
}

TEST(Feature2D, ComputeRefusesAnOctaveOutsideTheLevels) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  cv::Mat descriptors;
  for (int octave : {-1, 8}) {
    std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(100.f, 100.f, 31.f, -1.f, 0.f, octave)};
    try {
      opencv::Feature2D::create()->compute(gray, keypoints, descriptors);
      ADD_FAILURE() << "octave " << octave << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("octave " + std::to_string(octave)), std::string::npos)
          << e.what();
    }
  }
}

TEST(Feature2D, NoKeypointReleasesTheDescriptorsAsOrbDoes) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors(3, 32, CV_8U);
  opencv::Feature2D::create()->compute(gray, keypoints, descriptors);
  EXPECT_TRUE(descriptors.empty());
}

// An outside oracle: cv::ORB::compute keeps the angles it is given, so given the angles aief
// computed it describes level-0 keypoints (kept 31 pixels from the edge, cv::ORB's own border
// rule) as aief does, but for its blur, which differs from cv::GaussianBlur of the whole image by
// one grey level at about 2% of the pixels (tests/test_rbrief.cpp): on graf 502 of 534272 bits
// differ (0.09%).
TEST(Feature2D, ComputeAgreesWithCvOrbGivenTheSameAngles) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  std::vector<cv::KeyPoint> keypoints;
  cv::Ptr<cv::FastFeatureDetector> fast = cv::FastFeatureDetector::create(20, true);
  fast->detect(gray, keypoints);
  cv::KeyPointsFilter::runByImageBorder(keypoints, gray.size(), 31);
  ASSERT_GT(keypoints.size(), 500u);
  for (cv::KeyPoint& kp : keypoints) kp.octave = 0;
  cv::Mat ours, theirs;
  opencv::Feature2D::create()->compute(gray, keypoints, ours);
  std::vector<cv::KeyPoint> with_our_angles = keypoints;
  cv::ORB::create()->compute(gray, with_our_angles, theirs);
  ASSERT_EQ(with_our_angles.size(), keypoints.size());
  ASSERT_EQ(ours.size(), theirs.size());
  int differing_bits = 0;
  for (int r = 0; r < ours.rows; ++r)
    differing_bits += static_cast<int>(cv::norm(ours.row(r), theirs.row(r), cv::NORM_HAMMING));
  EXPECT_LT(differing_bits, ours.rows * 256 / 500)
      << "over " << ours.rows << " descriptors";  // < 0.2%
}

TEST(Feature2D, ColourImagesAreConvertedAsCvtColor) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  const cv::Ptr<cv::Feature2D> detector = opencv::Feature2D::create();
  std::vector<cv::KeyPoint> from_gray, from_bgr;
  cv::Mat d_gray, d_bgr;
  detector->detectAndCompute(gray, cv::noArray(), from_gray, d_gray);
  detector->detectAndCompute(bgr, cv::noArray(), from_bgr, d_bgr);
  EXPECT_EQ(first_difference(from_gray, d_gray, from_bgr, d_bgr), "");
  cv::Mat floats;
  gray.convertTo(floats, CV_32F);
  EXPECT_THROW(detector->detect(floats, from_gray), Error);
}

}  // namespace
}  // namespace aief

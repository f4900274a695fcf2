// OpenCV's invariance protocol for feature detectors and descriptors, run on aief beside cv::ORB
// on the bundled images, at the thresholds OpenCV sets for ORB. The protocol, as OpenCV's
// features2d tests describe it (test_detectors_invariance and test_descriptors_invariance), in
// this project's own code:
//
//   Two keypoints correspond when the discs of their sizes (radius size / 2), one mapped into the
//   other's image, overlap by at least half: intersection area / union area >= 0.5.
//   Rotation: the image is rotated about its centre by 0, 15, ..., 345 degrees onto a square
//   canvas of its diagonal, and so is a detection mask that leaves out a 16-pixel frame.
//   - detector rotation: each keypoint of the image, mapped by the rotation, takes the keypoint of
//     the rotated image it overlaps most; matched when that overlap is >= 0.5, and its angle is
//     consistent when it differs from the original angle + the rotation by < 15 degrees.
//     ORB: matched / keypoints >= 0.5 and consistent / matched >= 0.76, at every angle.
//   - descriptor rotation: the image's keypoints, mapped by the rotation (angle + rotation), are
//     described in the rotated image; each original descriptor takes its nearest rotated
//     descriptor (Hamming); right when that one's keypoint overlaps its own mapped keypoint by
//     >= 0.5. ORB: right / keypoints >= 0.99 at every angle.
//   Scale: the image is shrunk by 1.5, 2 and 2.5 (cv::INTER_LINEAR_EXACT).
//   - detector scale: each keypoint of the shrunk image, scaled back (position and size), takes
//     the keypoint of the original it overlaps most; matched when >= 0.5, and its size is
//     consistent when the smaller size is > 0.8 times the larger. ORB: matched / keypoints of the
//     shrunk image >= 0.08 and consistent / matched >= 0.49; and the shrunk image gives no more
//     keypoints than the original.
// OpenCV runs the rotation tests on tsukuba and the scale test on bikes img1; neither is bundled,
// so every test runs on graf, boat and leuven img1. Each figure is printed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/feature2d.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

constexpr double kPi = 3.14159265358979323846;

// OpenCV's thresholds for ORB.
constexpr float kMinOverlap = 0.5f;
constexpr float kMaxAngleError = 15.f;  // degrees
constexpr float kMinSizeRatio = 0.8f;
constexpr double kRotationMatched = 0.5, kRotationAngleConsistent = 0.76;
constexpr double kScaleMatched = 0.08, kScaleSizeConsistent = 0.49;
constexpr double kDescriptorRotationRight = 0.99;
constexpr int kMaskFrame = 16;
constexpr int kAngleStep = 15;

// Area of the intersection of two discs over the area of their union.
double overlap_ratio(cv::Point2f c0, double r0, cv::Point2f c1, double r1) {
  const double d = std::hypot(static_cast<double>(c0.x - c1.x), static_cast<double>(c0.y - c1.y));
  double intersection;
  if (d >= r0 + r1) {
    intersection = 0;
  } else if (d <= std::abs(r0 - r1)) {
    const double r = std::min(r0, r1);
    intersection = kPi * r * r;
  } else {
    // Two circular segments, each cut by the chord through the circles' crossing points.
    const double a0 = 2 * std::acos((r0 * r0 + d * d - r1 * r1) / (2 * r0 * d));
    const double a1 = 2 * std::acos((r1 * r1 + d * d - r0 * r0) / (2 * r1 * d));
    intersection = 0.5 * r0 * r0 * (a0 - std::sin(a0)) + 0.5 * r1 * r1 * (a1 - std::sin(a1));
  }
  return intersection / (kPi * (r0 * r0 + r1 * r1) - intersection);
}

double overlap_ratio(const cv::KeyPoint& a, cv::Point2f a_centre, const cv::KeyPoint& b) {
  return overlap_ratio(a_centre, 0.5 * a.size, b.pt, 0.5 * b.size);
}

struct Rotated {
  cv::Mat H;  // 3 x 3 CV_64F, original -> rotated pixels
  cv::Mat image, mask;
};

// The image and its mask turned by `degrees` about the image centre, onto a square canvas of the
// image's diagonal with the centre in the middle.
Rotated rotate(const cv::Mat& image, const cv::Mat& mask, int degrees) {
  const double diagonal =
      std::hypot(static_cast<double>(image.cols), static_cast<double>(image.rows));
  const double a = degrees * kPi / 180, c = std::cos(a), s = std::sin(a);
  const double cx = image.cols / 2, cy = image.rows / 2;  // OpenCV's integer centre
  Rotated out;
  out.H = (cv::Mat_<double>(3, 3) << c, -s, diagonal / 2 - (c * cx - s * cy), s, c,
           diagonal / 2 - (s * cx + c * cy), 0, 0, 1);
  const int side = static_cast<int>(std::lround(diagonal));
  cv::warpPerspective(image, out.image, out.H, {side, side});
  cv::warpPerspective(mask, out.mask, out.H, {side, side});
  return out;
}

cv::Point2f map_point(const cv::Mat& H, cv::Point2f p) {
  const double* h = H.ptr<double>();
  const double w = h[6] * p.x + h[7] * p.y + h[8];
  return {static_cast<float>((h[0] * p.x + h[1] * p.y + h[2]) / w),
          static_cast<float>((h[3] * p.x + h[4] * p.y + h[5]) / w)};
}

cv::Mat frame_mask(cv::Size size) {
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(kMaskFrame, kMaskFrame, size.width - 2 * kMaskFrame, size.height - 2 * kMaskFrame))
      .setTo(255);
  return mask;
}

// For each query keypoint (its centre mapped to `centres`), the index of the train keypoint it
// overlaps most (-1 for none) and that overlap.
void best_overlaps(const std::vector<cv::KeyPoint>& queries,
                   const std::vector<cv::Point2f>& centres, const std::vector<cv::KeyPoint>& train,
                   std::vector<int>& best, std::vector<double>& overlap) {
  best.assign(queries.size(), -1);
  overlap.assign(queries.size(), 0.0);
  for (std::size_t q = 0; q < queries.size(); ++q)
    for (std::size_t t = 0; t < train.size(); ++t) {
      const double o = overlap_ratio(queries[q], centres[q], train[t]);
      if (o > overlap[q]) {
        overlap[q] = o;
        best[q] = static_cast<int>(t);
      }
    }
}

double circular_difference_deg(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

struct Detector {
  std::string name;
  std::function<cv::Ptr<cv::Feature2D>()> make;
  std::function<cv::Ptr<cv::Feature2D>()>
      make_recomputing;  // aief with GivenAngles::recompute; null for cv::ORB
};

struct Param {
  Detector detector;
  std::string sequence;
};

void PrintTo(const Param& p, std::ostream* out) { *out << p.detector.name << " on " << p.sequence; }

std::string param_name(const testing::TestParamInfo<Param>& info) {
  std::string name = info.param.detector.name + "_" + info.param.sequence;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

class Invariance : public testing::TestWithParam<Param> {
 protected:
  cv::Mat image() const { return test::load_sample_gray(GetParam().sequence, "img1.png"); }
  cv::Ptr<cv::Feature2D> detector() const { return GetParam().detector.make(); }
  std::string label() const { return GetParam().detector.name + " on " + GetParam().sequence; }
};

TEST_P(Invariance, DetectorRotation) {
  const cv::Mat image0 = image();
  const cv::Mat mask0 = frame_mask(image0.size());
  const cv::Ptr<cv::Feature2D> detector = this->detector();
  std::vector<cv::KeyPoint> keypoints0;
  detector->detect(image0, keypoints0, mask0);
  ASSERT_GE(keypoints0.size(), 15u);
  double worst_matched = 1, worst_consistent = 1;
  for (int degrees = 0; degrees < 360; degrees += kAngleStep) {
    const Rotated r = rotate(image0, mask0, degrees);
    std::vector<cv::KeyPoint> keypoints1;
    detector->detect(r.image, keypoints1, r.mask);
    std::vector<cv::Point2f> centres;
    for (const cv::KeyPoint& kp : keypoints0) centres.push_back(map_point(r.H, kp.pt));
    std::vector<int> best;
    std::vector<double> overlap;
    best_overlaps(keypoints0, centres, keypoints1, best, overlap);
    int matched = 0, consistent = 0;
    for (std::size_t i = 0; i < keypoints0.size(); ++i) {
      if (best[i] < 0 || overlap[i] < kMinOverlap) continue;
      ++matched;
      const double expected = keypoints0[i].angle + degrees;
      consistent +=
          circular_difference_deg(expected, keypoints1[static_cast<std::size_t>(best[i])].angle) <
          kMaxAngleError;
    }
    const double matched_ratio =
        static_cast<double>(matched) / static_cast<double>(keypoints0.size());
    const double consistent_ratio = matched ? static_cast<double>(consistent) / matched : 0.0;
    EXPECT_GE(matched_ratio, kRotationMatched) << label() << " at " << degrees << " degrees";
    EXPECT_GE(consistent_ratio, kRotationAngleConsistent)
        << label() << " at " << degrees << " degrees";
    worst_matched = std::min(worst_matched, matched_ratio);
    worst_consistent = std::min(worst_consistent, consistent_ratio);
  }
  std::printf(
      "detector rotation, %s: %zu keypoints, worst over the angles: matched %.3f (>= %.2f), angle "
      "consistent %.3f (>= %.2f)\n",
      label().c_str(), keypoints0.size(), worst_matched, kRotationMatched, worst_consistent,
      kRotationAngleConsistent);
}

TEST_P(Invariance, DetectorScale) {
  const cv::Mat image0 = image();
  const cv::Ptr<cv::Feature2D> detector = this->detector();
  std::vector<cv::KeyPoint> keypoints0;
  detector->detect(image0, keypoints0);
  ASSERT_GE(keypoints0.size(), 15u);
  double worst_matched = 1, worst_consistent = 1;
  for (double scale : {1.5, 2.0, 2.5}) {
    cv::Mat image1;
    cv::resize(image0, image1, cv::Size(), 1 / scale, 1 / scale, cv::INTER_LINEAR_EXACT);
    std::vector<cv::KeyPoint> keypoints1;
    detector->detect(image1, keypoints1);
    ASSERT_GE(keypoints1.size(), 15u);
    EXPECT_LE(keypoints1.size(), keypoints0.size())
        << label() << ": more keypoints in the smaller image";
    std::vector<cv::KeyPoint> scaled_back = keypoints1;
    std::vector<cv::Point2f> centres;
    for (cv::KeyPoint& kp : scaled_back) {
      kp.pt *= static_cast<float>(scale);
      kp.size *= static_cast<float>(scale);
      centres.push_back(kp.pt);
    }
    std::vector<int> best;
    std::vector<double> overlap;
    best_overlaps(scaled_back, centres, keypoints0, best, overlap);
    int matched = 0, consistent = 0;
    for (std::size_t i = 0; i < scaled_back.size(); ++i) {
      if (best[i] < 0 || overlap[i] < kMinOverlap) continue;
      ++matched;
      const float a = scaled_back[i].size, b = keypoints0[static_cast<std::size_t>(best[i])].size;
      consistent += std::min(a, b) > kMinSizeRatio * std::max(a, b);
    }
    const double matched_ratio =
        static_cast<double>(matched) / static_cast<double>(keypoints1.size());
    const double consistent_ratio = matched ? static_cast<double>(consistent) / matched : 0.0;
    EXPECT_GE(matched_ratio, kScaleMatched) << label() << " at scale " << scale;
    EXPECT_GE(consistent_ratio, kScaleSizeConsistent) << label() << " at scale " << scale;
    worst_matched = std::min(worst_matched, matched_ratio);
    worst_consistent = std::min(worst_consistent, consistent_ratio);
  }
  std::printf(
      "detector scale, %s: %zu keypoints, worst over the scales: matched %.3f (>= %.2f), size "
      "consistent %.3f (>= %.2f)\n",
      label().c_str(), keypoints0.size(), worst_matched, kScaleMatched, worst_consistent,
      kScaleSizeConsistent);
}

// The descriptor rotation protocol with `detector`, each angle's ratio expected >= `threshold`;
// prints the worst.
void check_descriptor_rotation(const cv::Ptr<cv::Feature2D>& detector, const cv::Mat& image0,
                               double threshold, const std::string& label) {
  const cv::Mat mask0 = frame_mask(image0.size());
  std::vector<cv::KeyPoint> keypoints0;
  cv::Mat descriptors0;
  detector->detect(image0, keypoints0, mask0);
  ASSERT_GE(keypoints0.size(), 15u);
  detector->compute(image0, keypoints0, descriptors0);
  const cv::BFMatcher matcher(detector->defaultNorm());
  double worst_right = 1;
  int worst_degrees = 0;
  for (int degrees = 0; degrees < 360; degrees += kAngleStep) {
    const Rotated r = rotate(image0, mask0, degrees);
    std::vector<cv::KeyPoint> mapped = keypoints0;
    for (std::size_t i = 0; i < mapped.size(); ++i) {
      mapped[i].pt = map_point(r.H, mapped[i].pt);
      mapped[i].angle = static_cast<float>(std::fmod(mapped[i].angle + degrees, 360.0));
      mapped[i].class_id = static_cast<int>(i);
    }
    // compute() may remove keypoints; class_id says which of keypoints0 each one is.
    std::vector<cv::KeyPoint> keypoints1 = mapped;
    cv::Mat descriptors1;
    detector->compute(r.image, keypoints1, descriptors1);
    std::vector<cv::DMatch> matches;
    matcher.match(descriptors0, descriptors1, matches);
    int right = 0;
    for (const cv::DMatch& m : matches) {
      const cv::KeyPoint& own = mapped[static_cast<std::size_t>(m.queryIdx)];
      right += overlap_ratio(own, own.pt, keypoints1[static_cast<std::size_t>(m.trainIdx)]) >=
               kMinOverlap;
    }
    const double right_ratio = static_cast<double>(right) / static_cast<double>(keypoints0.size());
    EXPECT_GE(right_ratio, threshold)
        << label << " at " << degrees << " degrees (" << keypoints1.size() << " of "
        << keypoints0.size() << " described)";
    if (right_ratio < worst_right) {
      worst_right = right_ratio;
      worst_degrees = degrees;
    }
  }
  std::printf("descriptor rotation, %s: %zu keypoints, worst right %.3f at %d degrees (>= %.2f)\n",
              label.c_str(), keypoints0.size(), worst_right, worst_degrees, threshold);
}

// As OpenCV runs it: compute() is given the true angles (each original angle plus the rotation),
// and keeps them (cv::ORB always does; aief's detectors here are made with GivenAngles::keep).
TEST_P(Invariance, DescriptorRotation) {
  check_descriptor_rotation(detector(), image(), kDescriptorRotationRight, label());
}

// aief's default compute() re-estimates each angle on the rotated image, as detection does, so
// this measures the orientation too. Re-estimated on a re-interpolated image, some angles move
// enough to change the descriptor: 0.976-0.981 in the default mode and 0.962-0.972 in the paper's
// on the bundled images (even at 0 degrees, where the canvas shifts the image by a fraction of a
// pixel), where the protocol's given angles give >= 0.99. Checked against a floor of 0.95.
constexpr double kDescriptorRotationRightAnglesRecomputed = 0.95;

using InvarianceOfAief = Invariance;  // aief only: cv::ORB::compute always keeps the given angles

TEST_P(InvarianceOfAief, DescriptorRotationWithAnglesRecomputed) {
  check_descriptor_rotation(GetParam().detector.make_recomputing(), image(),
                            kDescriptorRotationRightAnglesRecomputed,
                            label() + ", angles recomputed");
}

Detector aief_detector(const std::string& name, Mode mode) {
  return {
      name,
      [mode] {
        return cv::Ptr<cv::Feature2D>(
            opencv::Feature2D::create(options_for_mode(mode), GivenAngles::keep));
      },
      [mode] { return cv::Ptr<cv::Feature2D>(opencv::Feature2D::create(options_for_mode(mode))); }};
}

// cv::ORB as OpenCV tests it (500 features) and with aief's 1000.
const Detector kDetectors[] = {
    {"cv-ORB", [] { return cv::Ptr<cv::Feature2D>(cv::ORB::create()); }, nullptr},
    {"cv-ORB-1000", [] { return cv::Ptr<cv::Feature2D>(cv::ORB::create(1000)); }, nullptr},
    aief_detector("aief", Mode::aief),
    aief_detector("aief-paper", Mode::aief_paper),
};

std::vector<Param> params(bool aief_only) {
  std::vector<Param> out;
  for (const Detector& d : kDetectors)
    if (!aief_only || d.make_recomputing)
      for (const char* sequence : {"graf", "boat", "leuven"}) out.push_back({d, sequence});
  return out;
}

INSTANTIATE_TEST_SUITE_P(OpenCvProtocol, Invariance, testing::ValuesIn(params(false)), param_name);
INSTANTIATE_TEST_SUITE_P(OpenCvProtocol, InvarianceOfAief, testing::ValuesIn(params(true)),
                         param_name);

}  // namespace
}  // namespace aief

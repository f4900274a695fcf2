// rBRIEF-256: bit for bit cv::ORB's descriptor on the same blurred image, close to it on our own
// Q8 blur, and nearly unchanged by a quarter turn of the image.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/kernels/gaussian7_rows.hpp"
#include "core/kernels/hamming_256_many.hpp"
#include "core/kernels/ic_moments.hpp"
#include "core/kernels/rbrief_describe.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

constexpr int kBytes = 32;

using test::gaussian7_opencv;
using test::gaussian7_ours;

// The image cv::ORB (4.x) describes at level 0: the input copied into a buffer with a 32-pixel
// REFLECT_101 border, then blurred in place as a window of that buffer. cv::GaussianBlur takes
// another code path for a window than for a whole image, and the two differ by one grey level
// at about 2% of the pixels, so the whole-image blur is not ORB's.
cv::Mat blur_as_orb_does(const cv::Mat& src) {
  constexpr int kOrbBorder = 32;  // max(edgeThreshold 31, ceil(15 * sqrt(2)), 9 / 2) + 1
  cv::Mat padded;
  cv::copyMakeBorder(src, padded, kOrbBorder, kOrbBorder, kOrbBorder, kOrbBorder,
                     cv::BORDER_REFLECT_101);
  cv::Mat window = padded(cv::Rect(kOrbBorder, kOrbBorder, src.cols, src.rows));
  cv::GaussianBlur(window, window, cv::Size(7, 7), 2, 2, cv::BORDER_REFLECT_101);
  return window.clone();
}

std::vector<float> ic_angles(const cv::Mat& raw, const std::vector<PixelPoint>& points) {
  const int n = static_cast<int>(points.size());
  std::vector<std::int32_t> m10(points.size()), m01(points.size());
  ic_moments_scalar(view_of(raw), points.data(), n, m10.data(), m01.data());
  std::vector<float> angles(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) angles[i] = ic_angle_deg(m10[i], m01[i]);
  return angles;
}

std::vector<std::uint8_t> describe_ours(const cv::Mat& blurred,
                                        const std::vector<PixelPoint>& points,
                                        const std::vector<float>& angles) {
  std::vector<std::uint8_t> descriptors(points.size() * kBytes);
  rbrief_describe_scalar(view_of(blurred), points.data(), angles.data(),
                         static_cast<int>(points.size()), descriptors.data());
  return descriptors;
}

// OpenCV's computeOrbDescriptors written out for one point: cvRound of the float-rotated pattern.
std::vector<std::uint8_t> describe_by_formula(const cv::Mat& blurred, PixelPoint point,
                                              float angle_deg) {
  const float angle = angle_deg * static_cast<float>(CV_PI / 180.f);
  const float a = static_cast<float>(std::cos(angle)), b = static_cast<float>(std::sin(angle));
  const auto value = [&](int px, int py) {
    const float fx = static_cast<float>(px), fy = static_cast<float>(py);
    return blurred.at<std::uint8_t>(point.y + cvRound(fx * b + fy * a),
                                    point.x + cvRound(fx * a - fy * b));
  };
  const auto pattern = orb_pattern_31();
  std::vector<std::uint8_t> descriptor(kBytes, 0);
  for (int i = 0; i < 256; ++i)
    if (value(pattern[i][0], pattern[i][1]) < value(pattern[i][2], pattern[i][3]))
      descriptor[static_cast<std::size_t>(i / 8)] |= static_cast<std::uint8_t>(1 << (i % 8));
  return descriptor;
}

// cv::ORB's descriptors for level-0 keypoints with the given angles, in our order; rows of points
// ORB dropped stay empty (kept[i] false). ORB blurs `raw` itself (7x7, sigma 2, REFLECT_101).
std::vector<std::uint8_t> describe_opencv(const cv::Mat& raw, const std::vector<PixelPoint>& points,
                                          const std::vector<float>& angles,
                                          std::vector<bool>& kept) {
  std::vector<cv::KeyPoint> keypoints;
  for (std::size_t i = 0; i < points.size(); ++i)
    keypoints.emplace_back(
        cv::Point2f(static_cast<float>(points[i].x), static_cast<float>(points[i].y)), 31.f,
        angles[i], 0.f, 0, static_cast<int>(i));
  cv::Mat descriptors;
  cv::ORB::create()->compute(raw, keypoints, descriptors);
  std::vector<std::uint8_t> ordered(points.size() * kBytes, 0);
  kept.assign(points.size(), false);
  for (std::size_t row = 0; row < keypoints.size(); ++row) {
    const auto i = static_cast<std::size_t>(keypoints[row].class_id);
    kept[i] = true;
    std::copy_n(descriptors.ptr<std::uint8_t>(static_cast<int>(row)), kBytes,
                ordered.data() + i * kBytes);
  }
  return ordered;
}

// The strongest FAST corners at least `margin` from every edge, ties by (y, x).
std::vector<PixelPoint> corners(const cv::Mat& raw, int margin, std::size_t count) {
  std::vector<cv::KeyPoint> found;
  cv::FAST(raw, found, 20, true);
  std::vector<cv::KeyPoint> inside;
  for (const auto& k : found) {
    const int x = static_cast<int>(k.pt.x), y = static_cast<int>(k.pt.y);
    if (x >= margin && y >= margin && x < raw.cols - margin && y < raw.rows - margin)
      inside.push_back(k);
  }
  std::sort(inside.begin(), inside.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
    if (a.response != b.response) return a.response > b.response;
    if (a.pt.y != b.pt.y) return a.pt.y < b.pt.y;
    return a.pt.x < b.pt.x;
  });
  std::vector<PixelPoint> points;
  for (std::size_t i = 0; i < std::min(count, inside.size()); ++i)
    points.push_back({static_cast<int>(inside[i].pt.x), static_cast<int>(inside[i].pt.y)});
  return points;
}

// Angles from the intensity centroid, then every 7.3 degrees, and the quarter turns exactly.
std::vector<float> test_angles(const cv::Mat& raw, const std::vector<PixelPoint>& points) {
  std::vector<float> angles = ic_angles(raw, points);
  const float fixed[] = {0.f, 90.f, 180.f, 270.f, 45.f, 359.999f};
  for (std::size_t i = 0; i < angles.size(); ++i) {
    if (i % 3 == 1) angles[i] = std::fmod(7.3f * static_cast<float>(i), 360.f);
    if (i % 50 < 6) angles[i] = fixed[i % 50];
  }
  return angles;
}

TEST(Rbrief, PatternIsOrbs) {
  const auto pattern = orb_pattern_31();
  const std::int8_t first[4] = {8, -3, 9, 5}, second[4] = {4, 2, 7, -12},
                    last[4] = {-1, -6, 0, -11};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(pattern[0][k], first[k]);
    EXPECT_EQ(pattern[1][k], second[k]);
    EXPECT_EQ(pattern[255][k], last[k]);
  }
}

TEST(Rbrief, RotatedSamplesStayInsideTheEdgeBorder) {
  const auto pattern = orb_pattern_31();
  int widest = 0;
  for (int step = 0; step < 3600; ++step) {
    const float angle = static_cast<float>(step) * 0.1f * static_cast<float>(CV_PI / 180.f);
    const float a = std::cos(angle), b = std::sin(angle);
    for (int i = 0; i < 256; ++i)
      for (int p = 0; p < 4; p += 2) {
        const float fx = pattern[i][p], fy = pattern[i][p + 1];
        widest = std::max(
            {widest, std::abs(cvRound(fx * a - fy * b)), std::abs(cvRound(fx * b + fy * a))});
      }
  }
  // Strictly inside, at most 18: the SIMD kernel (simd/rbrief_describe/portable.hpp) stores each
  // sample as an unsigned offset from the patch corner 18 rows and columns up-left of the point.
  EXPECT_LT(widest, kEdgeBorder);
  EXPECT_LE(widest, 18);
  // Whatever the angle: no pattern point is farther than 18.5 from the centre, so no rotated
  // offset rounds past 18.
  double radius = 0;
  for (int i = 0; i < 256; ++i)
    for (int p = 0; p < 4; p += 2)
      radius = std::max(radius, std::hypot(static_cast<double>(pattern[i][p]),
                                           static_cast<double>(pattern[i][p + 1])));
  EXPECT_LT(radius, kEdgeBorder - 0.5);
}

// The disc core/description/patch_blur.cpp blurs: every rotated sample whose |dy| rounds to d has
// |dx| <= kSampleHalfWidth[d], at 36000 angles (a hundredth of a degree apart, in the kernel's own
// float formula), and the table equals its derivation from the pattern's largest radius.
TEST(Rbrief, RotatedSamplesStayInsideTheirDisc) {
  const auto pattern = orb_pattern_31();
  int widest[kSampleReach + 1] = {};
  const float kRadiansPerDegree = static_cast<float>(CV_PI / 180.0);
  for (int step = 0; step < 36000; ++step) {
    const float angle = static_cast<float>(step) * 0.01f * kRadiansPerDegree;
    const float a = std::cos(angle), b = std::sin(angle);
    for (int i = 0; i < 256; ++i)
      for (int p = 0; p < 4; p += 2) {
        const float fx = pattern[i][p], fy = pattern[i][p + 1];
        const int dx = std::abs(cvRound(fx * a - fy * b)), dy = std::abs(cvRound(fx * b + fy * a));
        ASSERT_LE(dy, kSampleReach);
        widest[dy] = std::max(widest[dy], dx);
      }
  }
  double radius = 0;
  for (int i = 0; i < 256; ++i)
    for (int p = 0; p < 4; p += 2)
      radius = std::max(radius, std::hypot(static_cast<double>(pattern[i][p]),
                                           static_cast<double>(pattern[i][p + 1])));
  for (int d = 0; d <= kSampleReach; ++d) {
    EXPECT_LE(widest[d], kSampleHalfWidth[d]) << "|dy| = " << d;
    const double below = std::max(0.0, d - 0.5);
    const double bound = std::sqrt(radius * radius + 1e-3 - below * below) + 0.5;
    EXPECT_EQ(kSampleHalfWidth[d], static_cast<int>(std::floor(bound))) << "|dy| = " << d;
  }
}

TEST(Rbrief, EqualsTheFormulaOnAnyBlurredImage) {
  const cv::Mat raw = test::load_sample_gray("graf", "img1.png");
  const std::vector<PixelPoint> points = corners(raw, kEdgeBorder, 1000);
  ASSERT_EQ(points.size(), 1000u);
  const std::vector<float> angles = test_angles(raw, points);
  const cv::Mat blurred = gaussian7_opencv(raw);
  const std::vector<std::uint8_t> ours = describe_ours(blurred, points, angles);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::vector<std::uint8_t> formula = describe_by_formula(blurred, points[i], angles[i]);
    for (int byte = 0; byte < kBytes; ++byte)
      ASSERT_EQ(ours[i * kBytes + static_cast<std::size_t>(byte)],
                formula[static_cast<std::size_t>(byte)])
          << "point " << i << " (" << points[i].x << ", " << points[i].y << ") angle " << angles[i]
          << " byte " << byte;
  }
}

TEST(Rbrief, IdenticalToOpenCvOnTheImageOrbDescribes) {
  for (const char* sequence : {"graf", "boat"}) {
    const cv::Mat raw = test::load_sample_gray(sequence, "img1.png");
    const std::vector<PixelPoint> points = corners(raw, 32, 1000);
    ASSERT_GE(points.size(), 500u);
    const std::vector<float> angles = test_angles(raw, points);
    const std::vector<std::uint8_t> ours = describe_ours(blur_as_orb_does(raw), points, angles);
    std::vector<bool> kept;
    const std::vector<std::uint8_t> opencv = describe_opencv(raw, points, angles, kept);
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_TRUE(kept[i]) << sequence << ": cv::ORB dropped point " << i
                           << ", 32 px inside the image";
      for (int byte = 0; byte < kBytes; ++byte)
        ASSERT_EQ(ours[i * kBytes + static_cast<std::size_t>(byte)],
                  opencv[i * kBytes + static_cast<std::size_t>(byte)])
            << sequence << ": point " << i << " (" << points[i].x << ", " << points[i].y
            << ") angle " << angles[i] << " byte " << byte;
    }
  }
}

TEST(Rbrief, CloseToOpenCvOnOurOwnBlur) {
  for (const char* sequence : {"graf", "boat"}) {
    const cv::Mat raw = test::load_sample_gray(sequence, "img1.png");
    const std::vector<PixelPoint> points = corners(raw, 32, 1000);
    ASSERT_GE(points.size(), 500u);
    const std::vector<float> angles = test_angles(raw, points);
    const std::vector<std::uint8_t> ours = describe_ours(gaussian7_ours(raw), points, angles);
    std::vector<bool> kept;
    const std::vector<std::uint8_t> opencv = describe_opencv(raw, points, angles, kept);
    long bits = 0, differing = 0, identical_descriptors = 0, compared = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!kept[i]) continue;
      const std::uint32_t d =
          hamming_256_scalar(ours.data() + i * kBytes, opencv.data() + i * kBytes);
      bits += 256;
      differing += d;
      identical_descriptors += d == 0;
      ++compared;
    }
    ASSERT_GT(compared, 400);
    const double agreement = 1.0 - static_cast<double>(differing) / static_cast<double>(bits);
    std::cout << sequence << ": " << compared << " descriptors, bit agreement with cv::ORB "
              << agreement * 100 << "%, " << identical_descriptors << " identical\n";
    EXPECT_GE(agreement, 0.95) << sequence;
  }
}

TEST(Rbrief, QuarterTurnOfTheImageKeepsTheDescriptor) {
  const cv::Mat raw = test::load_sample_gray("graf", "img1.png");
  cv::Mat turned;
  cv::rotate(raw, turned, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (rows - 1 - y, x)
  const std::vector<PixelPoint> points = corners(raw, 40, 200);
  ASSERT_EQ(points.size(), 200u);
  std::vector<PixelPoint> turned_points;
  for (const PixelPoint& p : points) turned_points.push_back({raw.rows - 1 - p.y, p.x});

  const cv::Mat blurred = gaussian7_ours(raw), turned_blurred = gaussian7_ours(turned);
  // The Q8 blur is one rounding of a symmetric 2D sum, so it commutes with the quarter turn.
  cv::Mat blurred_then_turned;
  cv::rotate(blurred, blurred_then_turned, cv::ROTATE_90_CLOCKWISE);
  EXPECT_EQ(cv::countNonZero(blurred_then_turned != turned_blurred), 0);

  const std::vector<float> angles = ic_angles(raw, points),
                           turned_angles = ic_angles(turned, turned_points);
  const std::vector<std::uint8_t> before = describe_ours(blurred, points, angles);
  const std::vector<std::uint8_t> after =
      describe_ours(turned_blurred, turned_points, turned_angles);
  std::vector<std::uint32_t> distances;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double turn = std::fmod(turned_angles[i] - angles[i] + 720.0, 360.0);
    EXPECT_NEAR(turn, 90.0, 1.0) << "point " << i;
    distances.push_back(hamming_256_scalar(before.data() + i * kBytes, after.data() + i * kBytes));
  }
  std::sort(distances.begin(), distances.end());
  const std::uint32_t median = distances[distances.size() / 2];
  std::cout << "quarter turn: median Hamming " << median << ", 90th percentile "
            << distances[distances.size() * 9 / 10] << ", max " << distances.back() << " bits\n";
  EXPECT_LE(median, 10u);
}

}  // namespace
}  // namespace aief

// Intensity-centroid orientation: ORB-SLAM2's disc, exact moments, and a quarter turn of the
// patch turning the angle by 90 degrees.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "core/kernels/ic_moments.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

float angle_at(const cv::Mat& image, int x, int y) {
  const PixelPoint point{x, y};
  std::int32_t m10 = 0, m01 = 0;
  ic_moments_scalar(view_of(image), &point, 1, &m10, &m01);
  return ic_angle_deg(m10, m01);
}

double angle_difference(double a, double b) {
  double d = std::fmod(a - b + 540.0, 360.0) - 180.0;
  return d;
}

TEST(Orientation, DiscIsOrbSlam2s) {
  const int expected[16] = {15, 15, 15, 15, 14, 14, 14, 13, 13, 12, 11, 10, 9, 8, 6, 3};
  const int* umax = orientation_disc_umax();
  for (int v = 0; v <= 15; ++v) EXPECT_EQ(umax[v], expected[v]) << "row " << v;
}

TEST(Orientation, MomentsAreTheDefinition) {
  const cv::Mat image = test::random_image(64, 64, 4);
  const int* umax = orientation_disc_umax();
  std::int64_t m10 = 0, m01 = 0;
  for (int v = -15; v <= 15; ++v)
    for (int u = -umax[std::abs(v)]; u <= umax[std::abs(v)]; ++u) {
      m10 += u * image.at<std::uint8_t>(32 + v, 32 + u);
      m01 += v * image.at<std::uint8_t>(32 + v, 32 + u);
    }
  const PixelPoint point{32, 32};
  std::int32_t got10 = 0, got01 = 0;
  ic_moments_scalar(view_of(image), &point, 1, &got10, &got01);
  EXPECT_EQ(got10, m10);
  EXPECT_EQ(got01, m01);
}

TEST(Orientation, BrighterToTheRightPointsAlongX) {
  cv::Mat ramp(64, 64, CV_8UC1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      ramp.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(2 * x + 20);
  EXPECT_NEAR(angle_difference(angle_at(ramp, 32, 32), 0.0), 0.0, 1e-3);
  cv::Mat down;
  cv::transpose(ramp, down);  // brighter downwards: +y, 90 degrees in image coordinates
  EXPECT_NEAR(angle_difference(angle_at(down, 32, 32), 90.0), 0.0, 1e-3);
}

TEST(Orientation, QuarterTurnOfThePatchTurnsTheAngle) {
  const cv::Mat image = test::random_textured_image(96, 96, 12);
  cv::Mat rotated;
  cv::rotate(image, rotated, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (95 - y, x)
  int checked = 0;
  for (int y = 20; y < 76; y += 7)
    for (int x = 20; x < 76; x += 7) {
      const float before = angle_at(image, x, y);
      const float after = angle_at(rotated, 95 - y, x);
      EXPECT_NEAR(angle_difference(after, before + 90.0), 0.0, 1.0)
          << "at (" << x << ", " << y << ")";
      ++checked;
    }
  EXPECT_GT(checked, 50);
}

TEST(Orientation, EveryQuarterTurnOfARealImage) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  const int w = image.cols, h = image.rows;
  struct Turn {
    cv::RotateFlags flag;
    double degrees;  // image y points down, so clockwise on screen adds to the angle
  };
  for (const Turn turn : {Turn{cv::ROTATE_90_CLOCKWISE, 90.0}, Turn{cv::ROTATE_180, 180.0},
                          Turn{cv::ROTATE_90_COUNTERCLOCKWISE, 270.0}}) {
    cv::Mat rotated;
    cv::rotate(image, rotated, turn.flag);
    int checked = 0;
    for (int y = 40; y < h - 40; y += 37)
      for (int x = 40; x < w - 40; x += 41) {
        int rx = 0, ry = 0;
        if (turn.flag == cv::ROTATE_90_CLOCKWISE) {
          rx = h - 1 - y;
          ry = x;
        }
        if (turn.flag == cv::ROTATE_180) {
          rx = w - 1 - x;
          ry = h - 1 - y;
        }
        if (turn.flag == cv::ROTATE_90_COUNTERCLOCKWISE) {
          rx = y;
          ry = w - 1 - x;
        }
        const float before = angle_at(image, x, y), after = angle_at(rotated, rx, ry);
        EXPECT_NEAR(angle_difference(after, before + turn.degrees), 0.0, 1.0)
            << "turn " << turn.degrees << " at (" << x << ", " << y << "): " << before << " -> "
            << after;
        ++checked;
      }
    EXPECT_GT(checked, 200);
  }
}

TEST(Orientation, AnglesStayInRange) {
  EXPECT_EQ(ic_angle_deg(0, 0), 0.0f);
  for (int m10 : {-5, 0, 7})
    for (int m01 : {-3, 0, 9}) {
      const float a = ic_angle_deg(m10, m01);
      EXPECT_GE(a, 0.0f);
      EXPECT_LT(a, 360.0f);
    }
  EXPECT_LT(ic_angle_deg(1000000, -1), 360.0f);
  // -5.7e-7 degrees: 360 - 5.7e-7 rounds to 360.0f as a float, which must wrap to 0.
  EXPECT_EQ(ic_angle_deg(100000000, -1), 0.0f);
  EXPECT_EQ(ic_angle_deg(-7, 0), 180.0f);
  EXPECT_EQ(ic_angle_deg(0, -7), 270.0f);
}

}  // namespace
}  // namespace aief

// Q8 7x7 Gaussian: the taps, exact against the documented formula written out naively and
// against cv::GaussianBlur, and bands of rows equal to the whole.
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/kernels/gaussian7_rows.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using test::gaussian7_opencv;
using test::gaussian7_ours;

// BORDER_REFLECT_101 for offsets of at most size - 1 past either edge: -1 -> 1, size -> size - 2.
int reflect101(int i, int size) {
  if (i < 0) return -i;
  if (i >= size) return 2 * (size - 1) - i;
  return i;
}

// The header's formula, pixel by pixel: the whole horizontal plane first, then the vertical sum.
cv::Mat blur_documented(const cv::Mat& src) {
  const auto& taps = kGaussian7Q8;
  const int width = src.cols, height = src.rows;
  std::vector<std::uint32_t> h(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t sum = 0;
      for (int k = 0; k < 7; ++k)
        sum += taps[static_cast<std::size_t>(k)] *
               src.at<std::uint8_t>(y, reflect101(x + k - 3, width));
      h[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
        static_cast<std::size_t>(x)] = sum;
    }
  cv::Mat dst(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t sum = 0;
      for (int k = 0; k < 7; ++k)
        sum += taps[static_cast<std::size_t>(k)] *
               h[static_cast<std::size_t>(reflect101(y + k - 3, height)) *
                     static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(x)];
      dst.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((sum + 32768) >> 16);
    }
  return dst;
}

TEST(GaussianBlur, TapsAreASymmetricQ8Gaussian) {
  // OpenCV's taps: the sampled sigma-2 Gaussian in Q8, within one unit of round(256 g / sum g)
  // (its own fixed-point rounding moves the centre pair), symmetric, summing to exactly 256.
  double g[7], total = 0;
  for (int k = 0; k < 7; ++k) total += g[k] = std::exp(-(k - 3) * (k - 3) / (2.0 * 2.0 * 2.0));
  int sum = 0;
  for (int k = 0; k < 7; ++k) {
    const int tap = kGaussian7Q8[static_cast<std::size_t>(k)];
    sum += tap;
    EXPECT_LE(std::abs(tap - static_cast<int>(std::lround(256 * g[k] / total))), 2) << "tap " << k;
    EXPECT_EQ(tap, kGaussian7Q8[static_cast<std::size_t>(6 - k)]) << "tap " << k;
  }
  EXPECT_EQ(sum, 256);
}

TEST(GaussianBlur, EqualsTheDocumentedFormula) {
  int checked = 0;
  for (int width : {4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 32, 33, 63, 64, 65, 70, 127, 129})
    for (int height : {4, 5, 7, 8, 37}) {
      const cv::Mat src =
          test::random_image(width, height, static_cast<std::uint32_t>(width * 100 + height));
      EXPECT_EQ(test::first_pixel_difference(gaussian7_ours(src), blur_documented(src), 0), "")
          << width << "x" << height;
      ++checked;
    }
  for (const char* sequence : {"graf", "boat"}) {
    const cv::Mat src = test::load_sample_gray(sequence, "img1.png");
    EXPECT_EQ(test::first_pixel_difference(gaussian7_ours(src), blur_documented(src), 0), "")
        << sequence;
  }
  EXPECT_EQ(checked, 90);
}

TEST(GaussianBlur, FlatAndSaturatedImagesStayFlat) {
  for (int value : {0, 1, 128, 255}) {
    const cv::Mat src(9, 13, CV_8UC1, cv::Scalar(value));
    EXPECT_EQ(test::first_pixel_difference(gaussian7_ours(src), src, 0), "") << "value " << value;
  }
  // A checkerboard of 0 and 255 drives every partial sum to its extremes.
  cv::Mat board(16, 16, CV_8UC1);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) board.at<std::uint8_t>(y, x) = ((x + y) % 2) ? 255 : 0;
  EXPECT_EQ(test::first_pixel_difference(gaussian7_ours(board), blur_documented(board), 0), "");
}

std::vector<std::pair<std::string, cv::Mat>> opencv_comparison_images() {
  std::vector<std::pair<std::string, cv::Mat>> images;
  for (const char* sequence : {"graf", "boat"})
    images.emplace_back(sequence, test::load_sample_gray(sequence, "img1.png"));
  images.emplace_back("textured 200x150", test::random_textured_image(200, 150, 3));
  images.emplace_back("textured 33x7", test::random_textured_image(33, 7, 4));
  for (int size : {4, 7, 31, 64, 129})
    images.emplace_back("noise " + std::to_string(size),
                        test::random_image(size, size + 3, 5u + static_cast<std::uint32_t>(size)));
  return images;
}

TEST(GaussianBlur, IsCvGaussianBlurToTheByte) {
  // The same taps, separable order, REFLECT_101 border and single rounding as OpenCV's 8-bit
  // path: rBRIEF sees exactly the image ORB-SLAM2 and cv::ORB describe.
  for (const auto& [name, src] : opencv_comparison_images()) {
    EXPECT_EQ(test::first_pixel_difference(gaussian7_ours(src), gaussian7_opencv(src), 0), "")
        << name;
    EXPECT_EQ(test::first_pixel_difference(blur_documented(src), gaussian7_opencv(src), 0), "")
        << name;
  }
}

TEST(GaussianBlur, RowPiecesEqualTheWhole) {
  const cv::Mat src = test::load_sample_gray("graf", "img1.png");
  const cv::Mat whole = gaussian7_ours(src);
  cv::Mat pieces(src.size(), CV_8UC1, cv::Scalar(0));
  const std::vector<int> cuts = {0, 1, 3, 4, 10, 11, 250, src.rows - 2, src.rows - 1, src.rows};
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    cv::Mat band = pieces.rowRange(cuts[i], cuts[i + 1]);  // dst row 0 is blurred row cuts[i]
    gaussian7_rows_scalar(view_of(src), mutable_view_of(band), cuts[i], cuts[i + 1], 0, src.cols);
  }
  EXPECT_EQ(test::first_pixel_difference(pieces, whole, 0), "");
}

TEST(GaussianBlur, ColumnSpansEqualTheWholeAndLeaveTheRest) {
  const cv::Mat src = test::load_sample_gray("graf", "img1.png");
  const cv::Mat whole = gaussian7_ours(src);
  cv::Mat spans(src.size(), CV_8UC1, cv::Scalar(0));
  const std::vector<int> cuts = {0, 1, 3, 4, 40, 41, 600, src.cols - 3, src.cols - 1, src.cols};
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    gaussian7_rows_scalar(view_of(src), mutable_view_of(spans), 0, src.rows, cuts[i], cuts[i + 1]);
  EXPECT_EQ(test::first_pixel_difference(spans, whole, 0), "");

  cv::Mat canvas(src.size(), CV_8UC1, cv::Scalar(77));
  gaussian7_rows_scalar(view_of(src), mutable_view_of(canvas), 0, src.rows, 100, 139);
  EXPECT_EQ(test::first_pixel_difference(canvas.colRange(100, 139), whole.colRange(100, 139), 0),
            "");
  EXPECT_EQ(cv::countNonZero(canvas.colRange(0, 100) != 77) +
                cv::countNonZero(canvas.colRange(139, src.cols) != 77),
            0);
}

TEST(GaussianBlur, StridedViews) {
  const cv::Mat big = test::random_image(90, 50, 8);
  const cv::Mat src = big(cv::Rect(5, 3, 61, 33));
  cv::Mat canvas(40, 70, CV_8UC1, cv::Scalar(77));
  cv::Mat dst = canvas(cv::Rect(2, 4, 61, 33));
  gaussian7_rows_scalar(view_of(src), mutable_view_of(dst), 0, src.rows, 0, src.cols);
  EXPECT_EQ(test::first_pixel_difference(dst, blur_documented(src.clone()), 0), "");
  int outside_changed = 0;
  for (int y = 0; y < canvas.rows; ++y)
    for (int x = 0; x < canvas.cols; ++x) {
      const bool inside = x >= 2 && x < 63 && y >= 4 && y < 37;
      if (!inside && canvas.at<std::uint8_t>(y, x) != 77) ++outside_changed;
    }
  EXPECT_EQ(outside_changed, 0);
}

}  // namespace
}  // namespace aief

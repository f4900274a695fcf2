// Q8 bilinear pyramid step: the documented geometry and fixed point, within one grey level of
// cv::resize(INTER_LINEAR), row pieces equal to the whole, odd and strided images.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/kernels/resize_bilinear_rows.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

cv::Mat resize_ours(const cv::Mat& src, int dst_width, int dst_height) {
  const ResizePlan plan = make_resize_plan(src.cols, src.rows, dst_width, dst_height);
  cv::Mat dst(dst_height, dst_width, CV_8UC1, cv::Scalar(0));
  resize_bilinear_rows_scalar(view_of(src), plan, mutable_view_of(dst), 0, dst_height);
  return dst;
}

// The Q8 formula of the header written out with its own plan, pixel by pixel: fx in double,
// clamped to [0, src - 1], split into a left tap and a rounded Q8 weight.
std::pair<int, int> documented_tap(int i, int src, int dst) {
  double f = (i + 0.5) * src / dst - 0.5;
  f = std::clamp(f, 0.0, static_cast<double>(src - 1));
  int s = static_cast<int>(std::floor(f));
  int w = static_cast<int>(std::lround((f - s) * 256.0));
  if (w == 256) {
    ++s;
    w = 0;
  }
  if (s == src - 1) {
    s = src - 2;
    w = 256;
  }
  return {s, w};
}

cv::Mat resize_documented(const cv::Mat& src, int dst_width, int dst_height) {
  cv::Mat dst(dst_height, dst_width, CV_8UC1);
  for (int y = 0; y < dst_height; ++y) {
    const auto [sy, wy] = documented_tap(y, src.rows, dst_height);
    for (int x = 0; x < dst_width; ++x) {
      const auto [sx, wx] = documented_tap(x, src.cols, dst_width);
      const auto h = [&src, sx = sx, wx = wx](int row) {
        return src.at<std::uint8_t>(row, sx) * (256 - wx) + src.at<std::uint8_t>(row, sx + 1) * wx;
      };
      dst.at<std::uint8_t>(y, x) =
          static_cast<std::uint8_t>((h(sy) * (256 - wy) + h(sy + 1) * wy + 32768) >> 16);
    }
  }
  return dst;
}

int scaled(int size) { return static_cast<int>(std::lround(size / 1.2)); }

TEST(PyramidResize, PlanKeepsBothTapsInside) {
  for (const auto& [src, dst] : std::vector<std::pair<int, int>>{
           {2, 1}, {2, 2}, {3, 2}, {5, 4}, {37, 31}, {640, 533}, {7, 19}}) {
    const ResizePlan plan = make_resize_plan(src, 2, dst, 1);
    for (int i = 0; i < dst; ++i) {
      const int s = plan.x_index[static_cast<std::size_t>(i)];
      const int w = plan.x_weight[static_cast<std::size_t>(i)];
      EXPECT_GE(s, 0) << src << " -> " << dst << " at " << i;
      EXPECT_LT(s + 1, src) << src << " -> " << dst << " at " << i;
      EXPECT_LE(w, 256) << src << " -> " << dst << " at " << i;
      // The taps sample the clamped fx to within half a Q8 step.
      const double f = std::clamp((i + 0.5) * src / dst - 0.5, 0.0, static_cast<double>(src - 1));
      EXPECT_NEAR(s + w / 256.0, f, 0.5 / 256 + 1e-9) << src << " -> " << dst << " at " << i;
    }
  }
}

TEST(PyramidResize, ConstantImageStaysConstant) {
  for (int value : {0, 1, 127, 254, 255})
    for (const auto& [w, h] :
         std::vector<std::pair<int, int>>{{2, 2}, {3, 5}, {37, 29}, {640, 480}}) {
      const cv::Mat src(h, w, CV_8UC1, cv::Scalar(value));
      const cv::Mat dst = resize_ours(src, std::max(1, scaled(w)), std::max(1, scaled(h)));
      const cv::Mat expected(dst.size(), CV_8UC1, cv::Scalar(value));
      EXPECT_EQ(test::first_pixel_difference(dst, expected, 0), "")
          << "value " << value << ", " << w << "x" << h;
    }
}

TEST(PyramidResize, EqualsTheDocumentedFormula) {
  int sizes_checked = 0;
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{
           {2, 2}, {3, 3}, {5, 4}, {17, 9}, {37, 29}, {70, 3}, {127, 37}, {129, 37}}) {
    const cv::Mat src = test::random_image(w, h, static_cast<std::uint32_t>(w * 1000 + h));
    for (const auto& [dw, dh] :
         std::vector<std::pair<int, int>>{{std::max(1, scaled(w)), std::max(1, scaled(h))},
                                          {1, 1},
                                          {w, h},
                                          {w / 2 + 1, h / 2 + 1}}) {
      EXPECT_EQ(
          test::first_pixel_difference(resize_ours(src, dw, dh), resize_documented(src, dw, dh), 0),
          "")
          << w << "x" << h << " -> " << dw << "x" << dh;
      ++sizes_checked;
    }
  }
  const cv::Mat graf = test::load_sample_gray("graf", "img1.png");
  EXPECT_EQ(test::first_pixel_difference(
                resize_ours(graf, scaled(graf.cols), scaled(graf.rows)),
                resize_documented(graf, scaled(graf.cols), scaled(graf.rows)), 0),
            "");
  EXPECT_EQ(sizes_checked, 32);
}

TEST(PyramidResize, WithinOneOfOpenCvOnRealImages) {
  for (const char* sequence : {"graf", "boat"}) {
    cv::Mat level = test::load_sample_gray(sequence, "img1.png");
    // Level n from level n - 1, as the pyramid is built, for the eight ORB-SLAM2 levels.
    for (int n = 1; n < 8; ++n) {
      const int dw = scaled(level.cols), dh = scaled(level.rows);
      const cv::Mat ours = resize_ours(level, dw, dh);
      cv::Mat opencv;
      cv::resize(level, opencv, cv::Size(dw, dh), 0, 0, cv::INTER_LINEAR);
      EXPECT_EQ(test::first_pixel_difference(ours, opencv, 1), "") << sequence << " level " << n;
      level = ours;
    }
  }
}

TEST(PyramidResize, WithinOneOfOpenCvOnOddRandomImages) {
  for (const auto& [w, h] :
       std::vector<std::pair<int, int>>{{3, 3}, {5, 7}, {33, 17}, {69, 37}, {129, 31}, {31, 129}}) {
    const cv::Mat src = test::random_image(w, h, static_cast<std::uint32_t>(7 * w + h));
    for (const auto& [dw, dh] :
         std::vector<std::pair<int, int>>{{scaled(w), scaled(h)}, {w / 2, h / 2}, {w - 1, h - 1}}) {
      cv::Mat opencv;
      cv::resize(src, opencv, cv::Size(dw, dh), 0, 0, cv::INTER_LINEAR);
      EXPECT_EQ(test::first_pixel_difference(resize_ours(src, dw, dh), opencv, 1), "")
          << w << "x" << h << " -> " << dw << "x" << dh;
    }
  }
}

TEST(PyramidResize, RowPiecesEqualTheWhole) {
  const cv::Mat src = test::load_sample_gray("graf", "img1.png");
  const int dw = scaled(src.cols), dh = scaled(src.rows);
  const ResizePlan plan = make_resize_plan(src.cols, src.rows, dw, dh);
  const cv::Mat whole = resize_ours(src, dw, dh);
  cv::Mat pieces(dh, dw, CV_8UC1, cv::Scalar(0));
  const std::vector<int> cuts = {0, 1, 2, 7, 64, 65, 300, dh - 1, dh};
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    resize_bilinear_rows_scalar(view_of(src), plan, mutable_view_of(pieces), cuts[i], cuts[i + 1]);
  EXPECT_EQ(test::first_pixel_difference(pieces, whole, 0), "");
}

TEST(PyramidResize, StridedViewsReadAndWriteOnlyTheirPixels) {
  // Source and destination are windows of larger images: stride > width on both sides.
  const cv::Mat big = test::random_image(100, 60, 99);
  const cv::Mat src = big(cv::Rect(3, 5, 67, 41));
  const int dw = scaled(src.cols), dh = scaled(src.rows);
  cv::Mat canvas(dh + 4, dw + 9, CV_8UC1, cv::Scalar(77));
  cv::Mat dst = canvas(cv::Rect(4, 2, dw, dh));
  const ResizePlan plan = make_resize_plan(src.cols, src.rows, dw, dh);
  resize_bilinear_rows_scalar(view_of(src), plan, mutable_view_of(dst), 0, dh);
  EXPECT_EQ(test::first_pixel_difference(dst, resize_documented(src.clone(), dw, dh), 0), "");
  int outside_changed = 0;
  for (int y = 0; y < canvas.rows; ++y)
    for (int x = 0; x < canvas.cols; ++x) {
      const bool inside = x >= 4 && x < 4 + dw && y >= 2 && y < 2 + dh;
      if (!inside && canvas.at<std::uint8_t>(y, x) != 77) ++outside_changed;
    }
  EXPECT_EQ(outside_changed, 0);
}

}  // namespace
}  // namespace aief

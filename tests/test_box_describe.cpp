// The box descriptor (core/kernels/box_describe.hpp): the compiled-in table is the data file's,
// and the scalar reference equals an oracle that sums the boxes' pixels one by one and compares
// the means in exact rationals, inside the image and with clipped boxes at its edges.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/kernels/box_describe.hpp"
#include "core/kernels/integral_image.hpp"
#include "core/kernels/integral_image_row.hpp"
#include "core/kernels/kernel_table.hpp"
#include "simd/kernels.hpp"

namespace aief {
namespace {

GrayImage random_image(int width, int height, std::uint32_t seed) {
  GrayImage image(width, height);
  std::mt19937 rng(seed);
  for (int i = 0; i < width * height; ++i) image.data()[i] = static_cast<std::uint8_t>(rng() >> 24);
  return image;
}

// The contract written out independently: box centres in the contract's float arithmetic
// (rounded half to even), boxes clipped to the image, pixels summed one by one.
std::vector<std::uint8_t> oracle(const GrayImage& image, float x, float y, float angle_deg,
                                 float scale) {
  std::vector<std::uint8_t> out(32, 0);
  const float t = angle_deg * static_cast<float>(3.14159265358979323846 / 180.0);
  const float a = scale * static_cast<float>(std::cos(t));
  const float b = scale * static_cast<float>(std::sin(t));
  const auto box = [&](int px, int py, long r, long long& sum, long long& area) {
    const float fx = static_cast<float>(px), fy = static_cast<float>(py);
    const long cx = std::lrint(x + (fx * a - fy * b)), cy = std::lrint(y + (fx * b + fy * a));
    sum = area = 0;
    for (long v = std::max(0L, cy - r); v <= std::min<long>(image.height() - 1, cy + r); ++v)
      for (long u = std::max(0L, cx - r); u <= std::min<long>(image.width() - 1, cx + r); ++u) {
        sum += image.view().at(static_cast<int>(u), static_cast<int>(v));
        ++area;
      }
    if (area == 0) {  // wholly outside: the contract keeps the nearest row or column of pixels
      const long u0 = std::clamp(cx - r, 0L, static_cast<long>(image.width() - 1));
      const long u1 = std::clamp(cx + r + 1, 1L, static_cast<long>(image.width()));
      const long v0 = std::clamp(cy - r, 0L, static_cast<long>(image.height() - 1));
      const long v1 = std::clamp(cy + r + 1, 1L, static_cast<long>(image.height()));
      for (long v = v0; v < v1; ++v)
        for (long u = u0; u < u1; ++u) {
          sum += image.view().at(static_cast<int>(u), static_cast<int>(v));
          ++area;
        }
    }
  };
  for (int i = 0; i < kBoxTests; ++i) {
    const BoxTest& test = box_table()[i];
    const long r = std::lrint(scale * static_cast<float>(test.radius));
    long long s1, a1, s2, a2;
    box(test.x1, test.y1, r, s1, a1);
    box(test.x2, test.y2, r, s2, a2);
    // mean1 - mean2 <= threshold / 100, multiplied by 100 * a1 * a2 > 0.
    if (100 * (s1 * a2 - s2 * a1) <= test.threshold_hundredths * a1 * a2)
      out[static_cast<std::size_t>(i / 8)] |= static_cast<std::uint8_t>(1 << (i % 8));
  }
  return out;
}

TEST(BoxDescriptor, TheCompiledTableIsTheDataFile) {
  std::ifstream file(std::string(AIEF_DATA_DIR) + "/box_descriptor/" + box_table_name() + ".txt");
  ASSERT_TRUE(file) << box_table_name();
  std::string line;
  int i = 0;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    ASSERT_LT(i, kBoxTests);
    std::istringstream fields(line);
    int x1, y1, x2, y2, radius;
    double threshold;
    fields >> x1 >> y1 >> x2 >> y2 >> radius >> threshold;
    const BoxTest& test = box_table()[i];
    EXPECT_EQ(test.x1, x1) << "test " << i;
    EXPECT_EQ(test.y1, y1) << "test " << i;
    EXPECT_EQ(test.x2, x2) << "test " << i;
    EXPECT_EQ(test.y2, y2) << "test " << i;
    EXPECT_EQ(test.radius, radius) << "test " << i;
    EXPECT_EQ(test.threshold_hundredths, std::lround(threshold * 100)) << "test " << i;
    ++i;
  }
  EXPECT_EQ(i, kBoxTests);
}

TEST(BoxDescriptor, TeblidTableAsPublished) {
  if (std::string(box_table_name()) != "teblid_256") GTEST_SKIP() << "another table compiled in";
  // opencv_contrib's first test {25, 14, 13, 15, 6, 21.65f} and last {16, 20, 12, 19, 1, 2.75f},
  // origin moved from the corner to the centre (minus 16).
  const BoxTest& first = box_table()[0];
  EXPECT_EQ(first.x1, 9);
  EXPECT_EQ(first.y1, -2);
  EXPECT_EQ(first.x2, -3);
  EXPECT_EQ(first.y2, -1);
  EXPECT_EQ(first.radius, 6);
  EXPECT_EQ(first.threshold_hundredths, 2165);
  const BoxTest& last = box_table()[kBoxTests - 1];
  EXPECT_EQ(last.x1, 0);
  EXPECT_EQ(last.y1, 4);
  EXPECT_EQ(last.x2, -4);
  EXPECT_EQ(last.y2, 3);
  EXPECT_EQ(last.radius, 1);
  EXPECT_EQ(last.threshold_hundredths, 275);
}

TEST(BoxDescriptor, IntegralImageSumsEveryRectangle) {
  const GrayImage image = random_image(23, 17, 5);
  IntegralImage integral;
  integral.compute(image.view());
  const IntegralView v = integral.view();
  for (int y = 0; y <= image.height(); ++y)
    for (int x = 0; x <= image.width(); ++x) {
      std::uint32_t sum = 0;
      for (int j = 0; j < y; ++j)
        for (int i = 0; i < x; ++i) sum += image.view().at(i, j);
      ASSERT_EQ(v.row(y)[x], sum) << x << ", " << y;
    }
}

// The row kernel (core/kernels/integral_image_row.hpp) of every set against the sums written out,
// on widths around the vector widths and above a row near 2^32 (the entries wrap), and the
// integral image it makes equal to the scalar one.
TEST(BoxDescriptor, IntegralRowOfEverySetIsTheRunningSum) {
  for (int width : {1, 2, 7, 8, 9, 15, 16, 17, 31, 33, 64, 71}) {
    const GrayImage image = random_image(width, 3, 40 + static_cast<std::uint32_t>(width));
    std::vector<std::uint32_t> above(static_cast<std::size_t>(width) + 1), expected(above.size());
    for (std::size_t x = 0; x < above.size(); ++x)
      above[x] = 0xFFFFF000u + static_cast<std::uint32_t>(x * 977u % 4096u);
    for (int y = 0; y < image.height(); ++y) {
      std::uint32_t sum = 0;
      expected[0] = 0;
      for (int x = 0; x < width; ++x) {
        sum += image.view().at(x, y);
        expected[static_cast<std::size_t>(x) + 1] = above[static_cast<std::size_t>(x) + 1] + sum;
      }
      std::vector<std::uint32_t> out(above.size(), 12345u);
      integral_image_row_scalar(image.view().row(y), width, above.data(), out.data());
      EXPECT_EQ(out, expected) << "scalar, width " << width;
      for (KernelSet set : available_kernel_sets()) {
        std::fill(out.begin(), out.end(), 12345u);
        kernel_table(set).integral_image_row(image.view().row(y), width, above.data(), out.data());
        EXPECT_EQ(out, expected) << to_string(set) << ", width " << width;
      }
    }
  }
  const GrayImage image = random_image(301, 29, 9);
  IntegralImage scalar;
  scalar.compute(image.view());
  for (KernelSet set : available_kernel_sets()) {
    IntegralImage other;
    other.compute(image.view(), kernel_table(set));
    for (int y = 0; y <= image.height(); ++y)
      for (int x = 0; x <= image.width(); ++x)
        ASSERT_EQ(other.view().row(y)[x], scalar.view().row(y)[x]) << to_string(set);
  }
}

TEST(BoxDescriptor, ScalarReferenceEqualsThePixelByPixelOracle) {
  const GrayImage image = random_image(97, 83, 11);
  IntegralImage integral;
  integral.compute(image.view());
  std::vector<BoxPoint> points;
  std::vector<float> angles;
  // Inside, near every edge and corner (clipped boxes), and outside the image.
  for (int y = -4; y < image.height() + 4; y += 7)
    for (int x = -4; x < image.width() + 4; x += 5) {
      points.push_back({static_cast<float>(x), static_cast<float>(y)});
      angles.push_back(static_cast<float>((x * 31 + y * 17) % 360));
    }
  for (float scale : {kBoxLevelScale, 1.5f * kBoxLevelScale}) {
    std::vector<std::uint8_t> described(points.size() * 32);
    box_describe_scalar(integral.view(), points.data(), angles.data(),
                        static_cast<int>(points.size()), scale, described.data());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::vector<std::uint8_t> expected =
          oracle(image, points[k].x, points[k].y, angles[k], scale);
      ASSERT_TRUE(std::equal(expected.begin(), expected.end(), described.begin() + 32 * k))
          << "point (" << points[k].x << ", " << points[k].y << "), angle " << angles[k]
          << ", scale " << scale;
    }
  }
}

TEST(BoxDescriptor, FlatImageGivesEachTestTheSignOfItsThreshold) {
  GrayImage image(64, 64);
  std::fill(image.data(), image.data() + 64 * 64, std::uint8_t{77});
  IntegralImage integral;
  integral.compute(image.view());
  const BoxPoint point{32, 32};
  const float angle = 30;
  std::uint8_t described[32];
  box_describe_scalar(integral.view(), &point, &angle, 1, kBoxLevelScale, described);
  for (int i = 0; i < kBoxTests; ++i)  // mean 1 - mean 2 = 0 <= threshold
    EXPECT_EQ((described[i / 8] >> (i % 8)) & 1, box_table()[i].threshold_hundredths >= 0 ? 1 : 0)
        << "test " << i;
}

// A band of integral rows from its own origin row (zeros there, not the image's top), as the
// extractor holds it (core/description/box_on_integral_band.cpp), describes every point whose reach
// it holds as the whole integral image does, under every kernel set (the band is exactly the
// rows box_reach names, so a read outside it is one the sanitizer build reports).
TEST(BoxDescriptor, ABandFromAnyOriginRowDescribesAsTheWholeIntegral) {
  const GrayImage image = random_image(203, 157, 21);
  IntegralImage whole;
  whole.compute(image.view());
  const int reach = box_reach(kBoxLevelScale);
  ASSERT_GT(reach, 16);
  ASSERT_LT(reach, 40);
  const int width = image.width();
  const std::ptrdiff_t stride = width + 1;
  // Rows [origin, end) of the integral from `origin`.
  const auto band_from = [&](int origin, int end) {
    std::vector<std::uint32_t> band(static_cast<std::size_t>((end - origin) * stride), 0u);
    for (int r = origin + 1; r < end; ++r)
      integral_image_row_scalar(image.view().row(r - 1), width,
                                band.data() + (r - 1 - origin) * stride,
                                band.data() + (r - origin) * stride);
    return band;
  };
  std::mt19937 rng(5);
  for (int y : {0, 3, reach, reach + 1, 78, image.height() - reach - 1, image.height() - 1}) {
    std::vector<BoxPoint> points;
    std::vector<float> angles;
    for (int x = 0; x < width; x += 9) {
      points.push_back({static_cast<float>(x), static_cast<float>(y)});
      angles.push_back(static_cast<float>(rng() % 3600) / 10.0f);
    }
    const int n = static_cast<int>(points.size());
    std::vector<std::uint8_t> expected(points.size() * 32), described(expected.size());
    box_describe_scalar(whole.view(), points.data(), angles.data(), n, kBoxLevelScale,
                        expected.data());
    const int origin = std::max(0, y - reach), end = std::min(image.height() + 1, y + reach + 1);
    const std::vector<std::uint32_t> band = band_from(origin, end);
    const IntegralView view{band.data(), width, image.height(), stride, origin};
    box_describe_scalar(view, points.data(), angles.data(), n, kBoxLevelScale, described.data());
    EXPECT_EQ(described, expected) << "scalar, keypoint row " << y;
    for (KernelSet set : available_kernel_sets()) {
      std::fill(described.begin(), described.end(), std::uint8_t{0});
      kernel_table(set).box_describe(view, points.data(), angles.data(), n, kBoxLevelScale,
                                     described.data());
      EXPECT_EQ(described, expected) << to_string(set) << ", keypoint row " << y;
    }
  }
}

}  // namespace
}  // namespace aief

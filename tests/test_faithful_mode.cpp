// The faithful mode's pixels against OpenCV itself, no ORB-SLAM code needed: the OpenCV resize
// (core/kernels/resize_opencv_linear_rows.hpp) equals cv::resize(INTER_LINEAR) on random sizes,
// scale factors and images, and under every kernel set the whole pyramid equals ORB-SLAM2/3's
// ComputePyramid (each level cv::resize of the level above, to cvRound(cols / scale_n) x
// cvRound(rows / scale_n) with the scales in float) on odd-sized random images and the bundled
// photos. The keypoints' agreement with ORB-SLAM3's own ORBextractor is measured outside the
// repository (docs/slam.md, "The faithful mode").
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "aief/extractor.hpp"
#include "core/kernels/resize_opencv_linear_rows.hpp"
#include "simd/kernels.hpp"
#include "tests/features_hash.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

cv::Mat opencv_resize(const KernelTable& kernels, const OpenCvResizePlan& plan,
                      const cv::Mat& src) {
  cv::Mat out(plan.dst_height, plan.dst_width, CV_8UC1);
  kernels.resize_opencv_linear_rows(
      ImageView{src.data, src.cols, src.rows, static_cast<std::ptrdiff_t>(src.step)}, plan,
      MutableImageView{out.data, out.cols, out.rows, static_cast<std::ptrdiff_t>(out.step)}, 0,
      out.rows);
  return out;
}

std::string first_difference(const cv::Mat& expected, const cv::Mat& actual) {
  if (expected.size() != actual.size()) return "sizes differ";
  for (int y = 0; y < expected.rows; ++y)
    for (int x = 0; x < expected.cols; ++x)
      if (expected.at<std::uint8_t>(y, x) != actual.at<std::uint8_t>(y, x))
        return "at (" + std::to_string(x) + ", " + std::to_string(y) + "): cv::resize " +
               std::to_string(expected.at<std::uint8_t>(y, x)) + ", ours " +
               std::to_string(actual.at<std::uint8_t>(y, x));
  return "";
}

// Every kernel set: the scalar reference and the vector kernels
// (simd/resize_opencv_linear_rows_*.hpp), whose groups cover only some ratios and widths, the rest
// going to their scalar spans.
TEST(OpenCvResize, EqualsCvResizeOnRandomSizesScalesAndImagesUnderEveryKernelSet) {
  std::mt19937 rng(977);
  for (int trial = 0; trial < 300; ++trial) {
    const int width = 1 + static_cast<int>(rng() % 700), height = 1 + static_cast<int>(rng() % 500);
    int dst_width = 0, dst_height = 0;
    switch (trial % 4) {
      case 0:  // ORB-SLAM's ratio
        dst_width = cvRound(static_cast<float>(width) * (1.0f / 1.2f));
        dst_height = cvRound(static_cast<float>(height) * (1.0f / 1.2f));
        break;
      case 1:  // any ratio, both ways
        dst_width = 1 + static_cast<int>(rng() % 800);
        dst_height = 1 + static_cast<int>(rng() % 600);
        break;
      case 2:  // exact halving (OpenCV switches to INTER_AREA there)
        dst_width = std::max(1, width / 2);
        dst_height = std::max(1, height / 2);
        break;
      default:  // narrow outputs, below a vector's width
        dst_width = 1 + static_cast<int>(rng() % 20);
        dst_height = 1 + static_cast<int>(rng() % 20);
    }
    dst_width = std::max(dst_width, 1);
    dst_height = std::max(dst_height, 1);
    const cv::Mat src =
        trial % 2 ? test::random_image(width, height, rng())
                  : test::random_textured_image(std::max(width, 8), std::max(height, 8), rng());
    cv::Mat expected;
    cv::resize(src, expected, cv::Size(dst_width, dst_height), 0, 0, cv::INTER_LINEAR);
    const OpenCvResizePlan plan =
        make_opencv_resize_plan(src.cols, src.rows, dst_width, dst_height);
    for (const KernelSet set : available_kernel_sets())
      EXPECT_EQ(first_difference(expected, opencv_resize(kernel_table(set), plan, src)), "")
          << to_string(set) << ", " << src.cols << "x" << src.rows << " -> " << dst_width << "x"
          << dst_height;
  }
}

// ORB-SLAM2/3's ComputePyramid, its pixels: sizes from float scales, each level from the last.
std::vector<cv::Mat> orbslam_pyramid(const cv::Mat& image, int levels, float scale_factor) {
  std::vector<cv::Mat> pyramid{image};
  float scale = 1.0f;
  for (int n = 1; n < levels; ++n) {
    scale *= scale_factor;
    const float inverse = 1.0f / scale;
    const cv::Size size(cvRound(static_cast<float>(image.cols) * inverse),
                        cvRound(static_cast<float>(image.rows) * inverse));
    cv::Mat level;
    cv::resize(pyramid.back(), level, size, 0, 0, cv::INTER_LINEAR);
    pyramid.push_back(level);
  }
  return pyramid;
}

TEST(FaithfulMode, PyramidEqualsOrbSlamUnderEveryKernelSet) {
  std::vector<cv::Mat> images = {test::load_sample_gray("graf", "img1.png"),
                                 test::load_sample_gray("boat", "img1.png")};
  std::mt19937 rng(20261203);
  for (int i = 0; i < 4; ++i)
    images.push_back(test::random_textured_image(101 + 2 * static_cast<int>(rng() % 300),
                                                 77 + 2 * static_cast<int>(rng() % 200), rng()));
  for (const KernelSet set : available_kernel_sets())
    for (const cv::Mat& image : images)
      for (const double scale_factor : {1.2, 1.37}) {
        ExtractorOptions options = options_for_mode(Mode::faithful);
        options.kernels = set;
        options.scale_factor = scale_factor;
        Extractor extractor(options);
        const ImageView view{image.data, image.cols, image.rows,
                             static_cast<std::ptrdiff_t>(image.step)};
        (void)extractor.extract(view);
        const std::vector<cv::Mat> expected =
            orbslam_pyramid(image, options.n_levels, static_cast<float>(scale_factor));
        for (int n = 1; n < options.n_levels; ++n) {
          const ImageView level = extractor.pyramid_level(n);
          if (level.empty()) continue;  // too small to hold a keypoint: not built
          const cv::Mat ours(level.height, level.width, CV_8UC1,
                             const_cast<std::uint8_t*>(level.data),
                             static_cast<std::size_t>(level.stride));
          EXPECT_EQ(first_difference(expected[static_cast<std::size_t>(n)], ours), "")
              << to_string(set) << ", " << image.cols << "x" << image.rows << ", scale "
              << scale_factor << ", level " << n;
        }
      }
}

// The faithful mode's whole output, pinned: recorded from the scalar per-cell detection (commit
// a8ec39c, before the cells read the level's local-maxima bits), which the faithful keypoints were
// measured against ORB-SLAM3's with (docs/slam.md). Every kernel set and thread count, the bundled
// photos and a textured 640x480 frame.
TEST(FaithfulMode, ReproducesTheRecordedOutputToTheByte) {
  struct Pinned {
    const char* name;
    cv::Mat image;
    std::uint64_t hash;
  };
  const Pinned pinned[] = {
      {"graf", test::load_sample_gray("graf", "img1.png"), 0x96843c1c735beae9ull},
      {"boat", test::load_sample_gray("boat", "img1.png"), 0x9f17e9d414bf0c06ull},
      {"leuven", test::load_sample_gray("leuven", "img1.png"), 0x04952274c944fdacull},
      {"textured 640x480", test::random_textured_image(640, 480, 24), 0x9ae0ab26dae2bf3cull},
  };
  for (const Pinned& p : pinned)
    for (const KernelSet set : available_kernel_sets())
      for (const int threads : {1, 2}) {
        ExtractorOptions options = options_for_mode(Mode::faithful);
        options.kernels = set;
        options.threads = threads;
        char hash[32];
        std::snprintf(hash, sizeof hash, "0x%016llxull",
                      static_cast<unsigned long long>(
                          test::features_hash(Extractor(options).extract(view_of(p.image)))));
        char expected[32];
        std::snprintf(expected, sizeof expected, "0x%016llxull",
                      static_cast<unsigned long long>(p.hash));
        EXPECT_STREQ(hash, expected)
            << p.name << ", " << to_string(set) << ", " << threads << " threads";
      }
}

TEST(FaithfulMode, OrbSlamCellsTakeNoDetectionMask) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  const cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(255));
  Extractor extractor(options_for_mode(Mode::faithful));
  Features features;
  EXPECT_THROW(
      extractor.extract(
          ImageView{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)},
          ImageView{mask.data, mask.cols, mask.rows, static_cast<std::ptrdiff_t>(mask.step)},
          features),
      Error);
}

// With the entropy mask on, ORB-SLAM's cells keep only the candidates of the kept blocks.
TEST(FaithfulMode, OrbSlamCellsUnderTheEntropyMaskKeepOnlyKeptBlocks) {
  const cv::Mat image = test::load_sample_gray("boat", "img1.png");
  ExtractorOptions options = options_for_mode(Mode::faithful);
  const ImageView view{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
  const Features all = extract(view, options);
  options.entropy = EntropyMeasure::histogram;
  options.entropy_threshold = 7.0;
  const Features masked = extract(view, options);
  EXPECT_GT(masked.keypoints.size(), 0u);
  EXPECT_LT(masked.keypoints.size(), all.keypoints.size());
}

// ORB-SLAM's octree keeps up to 3 nodes over N; the faithful mode keeps them as it does.
TEST(FaithfulMode, KeepsOrbSlamsOvershootAndNeverFewerThanN) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  ExtractorOptions options = options_for_mode(Mode::faithful);
  const Features features = extract(
      ImageView{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)},
      options);
  EXPECT_GE(static_cast<int>(features.keypoints.size()), options.n_features);
  EXPECT_LE(static_cast<int>(features.keypoints.size()), options.n_features + 3 * options.n_levels);
}

}  // namespace
}  // namespace aief

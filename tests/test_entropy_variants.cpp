// The entropy-guided variants that never drop a region, each on its own: what each does on
// a synthetic image made for it, and that it keeps every region with candidates. The default
// (none) is the existing bytes (the hash tests); every kernel set and thread count giving the
// same bytes is tests/test_pipeline_differential.cpp.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "aief/extractor.hpp"
#include "core/distribution/quadtree_weighted.hpp"
#include "core/entropy/entropy_fast_threshold.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

ImageView view_of_mat(const cv::Mat& image) {
  return ImageView{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
}

// Left half: smoothed noise (high block entropy, corners of every strength). Right half: a
// two-level checkerboard of 6-pixel squares (1 bit a block, a corner at every crossing).
cv::Mat textured_left_checkerboard_right(int width, int height) {
  cv::Mat image = test::random_textured_image(width, height, 24);
  for (int y = 0; y < height; ++y)
    for (int x = width / 2; x < width; ++x)
      image.at<std::uint8_t>(y, x) = ((x / 6 + y / 6) % 2) ? 170 : 90;
  return image;
}

struct HalfCounts {
  int left = 0, right = 0;
};

HalfCounts count_halves(const Features& features, int width) {
  HalfCounts counts;
  for (const Keypoint& k : features.keypoints) (k.x < width / 2.0f ? counts.left : counts.right)++;
  return counts;
}

TEST(QuadtreeWeight, EntropyGivesTheHighEntropyHalfMoreKeypointsAndKeepsTheOther) {
  const cv::Mat image = textured_left_checkerboard_right(640, 480);
  ExtractorOptions options = options_for_mode(Mode::orbslam2);
  options.n_features = 500;
  const Features plain = Extractor(options).extract(view_of_mat(image));
  options.quadtree_weight = QuadtreeWeight::entropy;
  const Features weighted = Extractor(options).extract(view_of_mat(image));

  const HalfCounts before = count_halves(plain, image.cols);
  const HalfCounts after = count_halves(weighted, image.cols);
  EXPECT_EQ(plain.keypoints.size(), weighted.keypoints.size());  // the same budget
  EXPECT_GT(after.left, before.left) << "plain " << before.left << "/" << before.right
                                     << ", weighted " << after.left << "/" << after.right;
  EXPECT_GT(after.right, 0);  // the low-entropy half keeps keypoints: no region dropped
}

TEST(QuadtreeWeight, EveryLeafKeepsItsStrongestAndTheLevelKeepsExactlyN) {
  // Candidates on a 20 x 20 lattice; the left column's blocks weigh nothing.
  std::vector<Candidate> candidates;
  std::vector<std::int64_t> weights;
  for (int y = 20; y < 420; y += 20)
    for (int x = 20; x < 420; x += 20) {
      Candidate c{};
      c.x = x;
      c.y = y;
      c.score = static_cast<std::uint8_t>(10 + (x * 7 + y * 13) % 200);
      candidates.push_back(c);
      weights.push_back(x < 100 ? 0 : entropy_weight(6.0));
    }
  for (const int wanted : {1, 7, 50, 123, 400, 1000}) {
    std::vector<std::int32_t> selected;
    distribute_quadtree_weighted(candidates, weights, 16, 424, 16, 424, wanted, selected);
    const std::size_t expected = std::min<std::size_t>(wanted, candidates.size());
    ASSERT_EQ(selected.size(), expected) << "wanted " << wanted;
    std::vector<std::int32_t> sorted = selected;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end());
    if (wanted >= 50) {  // the weightless strip still holds a keypoint
      int in_strip = 0;
      for (std::int32_t i : selected) in_strip += candidates[static_cast<std::size_t>(i)].x < 100;
      EXPECT_GT(in_strip, 0) << "wanted " << wanted;
    }
  }
  // One candidate per leaf: with one leaf the strongest of all is kept.
  std::vector<std::int32_t> one;
  distribute_quadtree_weighted(candidates, weights, 16, 424, 16, 424, 1, one);
  for (std::size_t i = 0; i < candidates.size(); ++i)
    EXPECT_FALSE(stronger(candidates[i], candidates[static_cast<std::size_t>(one[0])]));
}

// Left half: smoothed noise at full contrast. Right half: the same texture squeezed into 96 gray
// levels (weak texture, lower block entropy): its blocks hold a few corners at 20 and more below.
cv::Mat textured_left_weak_right(int width, int height) {
  cv::Mat image = test::random_textured_image(width, height, 25);
  for (int y = 0; y < height; ++y)
    for (int x = width / 2; x < width; ++x) {
      std::uint8_t& pixel = image.at<std::uint8_t>(y, x);
      pixel = static_cast<std::uint8_t>(100 + pixel * 96 / 255);
    }
  return image;
}

TEST(FastThresholdFrom, RuleIsMonotoneFromTheRetryThresholdToTheFastThreshold) {
  ExtractorOptions options;  // 20 / 7
  EXPECT_EQ(entropy_fast_threshold(0.0, options), 7);
  EXPECT_EQ(entropy_fast_threshold(3.0, options), 13);  // 7 + 13 * 3 / 6, rounded down
  EXPECT_EQ(entropy_fast_threshold(6.0, options), 20);
  EXPECT_EQ(entropy_fast_threshold(8.0, options), 20);
  int previous = 0;
  for (int q = 0; q <= 8 * 256; ++q) {
    const int threshold = entropy_fast_threshold(q / 256.0, options);
    EXPECT_GE(threshold, previous);
    previous = threshold;
  }
}

TEST(FastThresholdFrom, EntropyGivesTheWeakTextureHalfMoreKeypoints) {
  const cv::Mat image = textured_left_weak_right(640, 480);
  ExtractorOptions options = options_for_mode(Mode::orbslam2);
  options.n_features = 2000;
  const Features plain = Extractor(options).extract(view_of_mat(image));
  options.fast_threshold_from = FastThresholdFrom::entropy;
  const Features lowered = Extractor(options).extract(view_of_mat(image));

  const HalfCounts before = count_halves(plain, image.cols);
  const HalfCounts after = count_halves(lowered, image.cols);
  EXPECT_GT(after.right, before.right) << "plain " << before.left << "/" << before.right
                                       << ", entropy " << after.left << "/" << after.right;
}

}  // namespace
}  // namespace aief

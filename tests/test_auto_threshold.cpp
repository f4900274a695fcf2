// The pair-free automatic entropy threshold: Otsu's split of the block entropies, never
// dropping more than a quarter of the blocks, only when they form two classes (the aief mode),
// and what a frame does with it.
#include <random>

#include <gtest/gtest.h>

#include "aief/extractor.hpp"
#include "core/frame/auto_threshold.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

int kept(const std::vector<double>& entropies, double threshold) {
  int count = 0;
  for (double e : entropies) count += e > threshold ? 1 : 0;
  return count;
}

TEST(AutoThreshold, SplitsTwoPopulationsBetweenThem) {
  std::mt19937 rng(1);
  std::normal_distribution<double> flat(1.5, 0.3), textured(6.5, 0.4);
  std::vector<double> entropies;
  for (int i = 0; i < 200; ++i) entropies.push_back(flat(rng));  // 20% flat blocks
  for (int i = 0; i < 800; ++i) entropies.push_back(textured(rng));
  for (const bool require_two_classes : {false, true}) {
    std::vector<double> copy = entropies;
    const AutoThreshold split = auto_entropy_threshold(copy, require_two_classes);
    const double threshold = split.threshold_bits;
    // Every flat block dropped, every textured one kept.
    EXPECT_EQ(kept(std::vector<double>(entropies.begin(), entropies.begin() + 200), threshold), 0)
        << "F = " << threshold;
    EXPECT_EQ(kept(std::vector<double>(entropies.begin() + 200, entropies.end()), threshold), 800)
        << "F = " << threshold;
    EXPECT_GT(split.effectiveness, 0.9);  // two distinct populations
  }
}

TEST(AutoThreshold, KeepsThreeQuartersOfAnEvenlyTexturedScene) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> texture(5.0, 7.5);
  std::vector<double> entropies;
  for (int i = 0; i < 1000; ++i) entropies.push_back(texture(rng));
  std::vector<double> copy = entropies;
  const double threshold = auto_entropy_threshold(copy, false).threshold_bits;
  EXPECT_GT(threshold, 5.0);                   // Otsu alone cuts through the texture ...
  EXPECT_GE(kept(entropies, threshold), 750);  // ... a quarter at most
}

// Otsu's effectiveness of one population: 2/pi for a normal distribution, 3/4 for a uniform one.
// Neither has two classes, so with the test every block is kept.
TEST(AutoThreshold, KeepsEveryBlockOfOnePopulation) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(6.0, 0.5);
  std::uniform_real_distribution<double> uniform(5.0, 7.5);
  std::vector<double> one_normal, one_uniform;
  for (int i = 0; i < 4000; ++i) {
    one_normal.push_back(normal(rng));
    one_uniform.push_back(uniform(rng));
  }
  std::vector<double> copy = one_normal;
  const AutoThreshold from_normal = auto_entropy_threshold(copy, true);
  EXPECT_NEAR(from_normal.effectiveness, 2.0 / 3.14159265358979, 0.02);
  EXPECT_EQ(from_normal.threshold_bits, 0.0);
  copy = one_uniform;
  const AutoThreshold from_uniform = auto_entropy_threshold(copy, true);
  EXPECT_NEAR(from_uniform.effectiveness, 0.75, 0.02);
  EXPECT_LT(from_uniform.effectiveness, kAutoMinEffectiveness);
  EXPECT_EQ(from_uniform.threshold_bits, 0.0);
  // Without the test, Otsu's split of the same entropies drops blocks.
  copy = one_normal;
  EXPECT_GT(auto_entropy_threshold(copy, false).threshold_bits, 5.0);
}

// A small low-information class (a fifth of the blocks: sky, a flat wall) beside the texture is
// a second class: the test lets Otsu's split drop it.
TEST(AutoThreshold, DropsASmallLowInformationClass) {
  std::mt19937 rng(4);
  std::normal_distribution<double> flat(2.5, 0.6), textured(6.3, 0.5);
  std::vector<double> entropies;
  for (int i = 0; i < 300; ++i) entropies.push_back(flat(rng));
  for (int i = 0; i < 1200; ++i) entropies.push_back(textured(rng));
  std::vector<double> copy = entropies;
  const AutoThreshold split = auto_entropy_threshold(copy, true);
  EXPECT_GE(split.effectiveness, kAutoMinEffectiveness);
  EXPECT_GT(split.threshold_bits, 3.5);
  EXPECT_LT(split.threshold_bits, 5.0);
}

TEST(AutoThreshold, DegenerateInputs) {
  std::vector<double> none;
  for (const bool require_two_classes : {false, true}) {
    EXPECT_EQ(auto_entropy_threshold(none, require_two_classes).threshold_bits, 0.0);
    std::vector<double> same(50, 3.0);
    const AutoThreshold split = auto_entropy_threshold(same, require_two_classes);
    EXPECT_LT(split.threshold_bits, 3.0);  // every block kept
    EXPECT_GE(split.threshold_bits, 0.0);
    EXPECT_EQ(split.effectiveness, 0.0);
  }
}

TEST(AutoThreshold, FrameUsesItAndReportsIt) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  ExtractorOptions options;
  options.auto_threshold = true;
  options.auto_requires_two_classes = false;  // graf is texture everywhere: Otsu's split alone
  const Features a = extract(view_of(gray), options);
  EXPECT_GT(a.info.entropy_threshold_requested, 0.0);
  EXPECT_GE(a.info.blocks_kept, a.info.blocks_total * 3 / 4);
  EXPECT_EQ(static_cast<int>(a.keypoints.size()), options.n_features);
  // Same F given by hand: same bytes.
  ExtractorOptions fixed;
  fixed.entropy_threshold = a.info.entropy_threshold_used;
  const Features b = extract(view_of(gray), fixed);
  EXPECT_EQ(a.descriptors, b.descriptors);
}

TEST(AutoThreshold, FrameOfOneTextureKeepsEveryBlock) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  ExtractorOptions options;  // the aief mode: two classes required
  options.auto_threshold = true;
  const Features features = extract(view_of(gray), options);
  EXPECT_EQ(features.info.entropy_threshold_requested, 0.0);
  EXPECT_GT(features.info.auto_threshold_effectiveness, 0.0) << "the reason F = 0 is reported";
  EXPECT_LT(features.info.auto_threshold_effectiveness, kAutoMinEffectiveness);
  EXPECT_EQ(features.info.blocks_kept, features.info.blocks_total);
  EXPECT_EQ(static_cast<int>(features.keypoints.size()), options.n_features);
}

TEST(AutoThreshold, FrameWithASmoothPartDropsIt) {
  // graf with its left fifth replaced by a gentle ramp (a few gray levels per block: low entropy,
  // not uniform): two classes, and the ramp's blocks are dropped.
  cv::Mat gray = test::load_sample_gray("graf", "img1.png").clone();
  const int ramp_end = gray.cols / 5;
  for (int y = 0; y < gray.rows; ++y)
    for (int x = 0; x < ramp_end; ++x)
      gray.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(60 + x / 8);
  ExtractorOptions options;
  options.auto_threshold = true;
  const Features features = extract(view_of(gray), options);
  EXPECT_GT(features.info.entropy_threshold_requested, 2.0);
  EXPECT_GE(features.info.auto_threshold_effectiveness, kAutoMinEffectiveness);
  EXPECT_LT(features.info.blocks_kept, features.info.blocks_total * 9 / 10);
  int in_ramp = 0;  // a block straddling the edge of the ramp holds texture: 40 px of margin
  for (const Keypoint& kp : features.keypoints) in_ramp += kp.x < ramp_end - 40 ? 1 : 0;
  EXPECT_EQ(in_ramp, 0);
}

}  // namespace
}  // namespace aief

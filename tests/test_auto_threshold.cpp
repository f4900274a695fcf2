// The pair-free automatic entropy threshold: Otsu's split of the block entropies, never
// dropping more than a quarter of the blocks, and what a frame does with it.
#include <random>

#include <gtest/gtest.h>

#include "aief/extractor.hpp"
#include "core/auto_threshold.hpp"
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
  for (int i = 0; i < 200; ++i) entropies.push_back(flat(rng));   // 20% flat blocks
  for (int i = 0; i < 800; ++i) entropies.push_back(textured(rng));
  std::vector<double> copy = entropies;
  const double threshold = auto_entropy_threshold(copy);
  // Every flat block dropped, every textured one kept.
  EXPECT_EQ(kept(std::vector<double>(entropies.begin(), entropies.begin() + 200), threshold), 0) << "F = " << threshold;
  EXPECT_EQ(kept(std::vector<double>(entropies.begin() + 200, entropies.end()), threshold), 800) << "F = " << threshold;
}

TEST(AutoThreshold, KeepsThreeQuartersOfAnEvenlyTexturedScene) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> texture(5.0, 7.5);
  std::vector<double> entropies;
  for (int i = 0; i < 1000; ++i) entropies.push_back(texture(rng));
  std::vector<double> copy = entropies;
  const double threshold = auto_entropy_threshold(copy);
  EXPECT_GE(kept(entropies, threshold), 750);
}

TEST(AutoThreshold, DegenerateInputs) {
  std::vector<double> none;
  EXPECT_EQ(auto_entropy_threshold(none), 0.0);
  std::vector<double> same(50, 3.0);
  const double threshold = auto_entropy_threshold(same);
  EXPECT_LT(threshold, 3.0);  // every block kept
  EXPECT_GE(threshold, 0.0);
}

TEST(AutoThreshold, FrameUsesItAndReportsIt) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  ExtractorOptions options;
  options.auto_threshold = true;
  const Features a = extract(test::view_of(gray), options);
  EXPECT_GT(a.info.entropy_threshold_requested, 0.0);
  EXPECT_GE(a.info.blocks_kept, a.info.blocks_total * 3 / 4);
  EXPECT_EQ(static_cast<int>(a.keypoints.size()), options.n_features);
  // Same F given by hand: same bytes.
  ExtractorOptions fixed;
  fixed.entropy_threshold = a.info.entropy_threshold_used;
  const Features b = extract(test::view_of(gray), fixed);
  EXPECT_EQ(a.descriptors, b.descriptors);
}

}  // namespace
}  // namespace aief

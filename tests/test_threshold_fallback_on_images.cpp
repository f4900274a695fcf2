// The shortfall rule of the aief mode (core/threshold_fallback.hpp): the budget a
// level short of candidates leaves undelivered goes to the levels with candidates to spare, so the
// frame delivers min(N, candidates in the kept blocks) at every kernel set and thread count.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <opencv2/core.hpp>

#include "aief/extractor.hpp"
#include "core/level_geometry.hpp"
#include "core/threshold_fallback.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

TEST(LevelShortfall, GoesToTheFinestLevelsWithCandidatesToSpare) {
  std::vector<int> raised;
  // Level 1 is 30 short; level 0 can take 10 more, level 2 is short too, level 3 takes the rest.
  EXPECT_TRUE(raise_budgets_for_shortfall({100, 80, 60, 40}, {110, 50, 55, 500}, raised));
  EXPECT_EQ(raised, (std::vector<int>{110, 80, 60, 65}));
  // Not enough anywhere: every level with spare candidates gives them all.
  EXPECT_TRUE(raise_budgets_for_shortfall({100, 80}, {105, 0}, raised));
  EXPECT_EQ(raised, (std::vector<int>{105, 80}));
  // No shortfall, or nobody to take it: the budgets stay.
  EXPECT_FALSE(raise_budgets_for_shortfall({100, 80}, {100, 900}, raised));
  EXPECT_EQ(raised, (std::vector<int>{100, 80}));
  EXPECT_FALSE(raise_budgets_for_shortfall({100, 80}, {10, 80}, raised));
  EXPECT_EQ(raised, (std::vector<int>{100, 80}));
}

// Gray squares on a flat field: about the same corners on every level, so the fine levels, with
// the largest budgets, are short of candidates while the coarse ones have plenty.
cv::Mat sparse_squares() {
  cv::Mat image(480, 640, CV_8UC1, cv::Scalar(90));
  for (int y = 40; y + 16 < image.rows - 40; y += 48)
    for (int x = 40; x + 16 < image.cols - 40; x += 48)
      image(cv::Rect(x, y, 16, 16)).setTo(cv::Scalar(200));
  return image;
}

bool same_bytes(const Features& a, const Features& b) {
  if (a.keypoints.size() != b.keypoints.size() || a.descriptors != b.descriptors) return false;
  for (std::size_t i = 0; i < a.keypoints.size(); ++i)
    if (std::memcmp(&a.keypoints[i], &b.keypoints[i], sizeof(Keypoint)) != 0) return false;
  return true;
}

TEST(LevelShortfall, AiefModeDeliversTheCountAskedForWhenALevelIsShort) {
  const cv::Mat image = sparse_squares();
  ExtractorOptions options = options_for_mode(Mode::aief);
  options.n_features = 600;
  options.kernels = KernelSet::scalar;
  options.threads = 1;
  const Features features = extract(view_of(image), options);

  const std::vector<LevelGeometry> levels = level_geometry(image.cols, image.rows, options);
  std::vector<int> per_level(levels.size(), 0);
  for (const Keypoint& kp : features.keypoints) ++per_level[static_cast<std::size_t>(kp.octave)];
  int short_levels = 0, raised_levels = 0;
  for (std::size_t n = 0; n < levels.size(); ++n) {
    short_levels += per_level[n] < levels[n].n_features;
    raised_levels += per_level[n] > levels[n].n_features;
  }
  ASSERT_GT(short_levels, 0) << "the case must have a level short of candidates";
  EXPECT_GT(raised_levels, 0) << "the shortfall must be delivered by another level";
  EXPECT_EQ(static_cast<int>(features.keypoints.size()), options.n_features);

  // The paper mode keeps its rule: the short level's budget is lost there.
  ExtractorOptions paper = options_for_mode(Mode::aief_paper);
  paper.n_features = options.n_features;
  EXPECT_LT(static_cast<int>(extract(view_of(image), paper).keypoints.size()), options.n_features);

  // The same bytes at every kernel set and thread count.
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 5);
  for (KernelSet set : available_kernel_sets())
    for (int threads : {1, 2, 5}) {
      ExtractorOptions other = options;
      other.kernels = set;
      other.threads = threads;
      EXPECT_TRUE(same_bytes(features, Extractor(other).extract(view_of(image))))
          << to_string(set) << " at " << threads << " thread(s)";
    }
}

}  // namespace
}  // namespace aief

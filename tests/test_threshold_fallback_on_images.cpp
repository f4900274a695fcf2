// The threshold fallback policy (core/entropy/threshold_fallback.hpp) on an image, through the
// extractor: in the aief mode, the budget a level short of candidates leaves undelivered goes to
// the levels with candidates to spare, so the frame delivers min(N, candidates in the kept blocks)
// at every kernel set and thread count. The policy on a table, no image:
// tests/test_threshold_fallback.cpp.
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <opencv2/core.hpp>

#include "aief/extractor.hpp"
#include "core/level/level_geometry.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

// Gray squares on a flat field: about the same corners on every level, so the fine levels, with
// the largest budgets, are short of candidates while the coarse ones have plenty.
cv::Mat sparse_squares() {
  cv::Mat image(480, 640, CV_8UC1, cv::Scalar(90));
  for (int y = 40; y + 16 < image.rows - 40; y += 48)
    for (int x = 40; x + 16 < image.cols - 40; x += 48)
      image(cv::Rect(x, y, 16, 16)).setTo(cv::Scalar(200));
  return image;
}

using test::same_bytes;

TEST(ThresholdFallbackOnImages, AiefModeDeliversTheCountAskedForWhenALevelIsShort) {
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

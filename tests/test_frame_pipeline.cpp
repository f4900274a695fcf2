// The frame pipeline (core/frame/frame_pipeline.hpp) with a stage clock gives the bytes it gives
// without one, and the clock hears from every stage: what aief bench times is what extract runs.
#include <cstdint>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "aief/extractor.hpp"
#include "core/frame/frame_pipeline.hpp"
#include "core/frame/stage_times.hpp"
#include "simd/kernels.hpp"

namespace aief {
namespace {

// Squares of random gray on a flat field, larger on the left half, none on the right third:
// blocks of many entropies, and flat ones.
GrayImage squares_image() {
  GrayImage image(400, 300);
  MutableImageView view = image.mutable_view();
  std::mt19937 rng(7);
  for (int y = 0; y < view.height; ++y)
    std::memset(view.row(y), 100, static_cast<std::size_t>(view.width));
  for (int y = 10; y + 12 < view.height - 10; y += 14)
    for (int x = 10; x + 12 < 2 * view.width / 3; x += 14) {
      const std::uint8_t gray = static_cast<std::uint8_t>(rng() % 256);
      const int side = x < view.width / 2 ? 10 : 6;
      for (int dy = 0; dy < side; ++dy)
        std::memset(view.row(y + dy) + x, gray, static_cast<std::size_t>(side));
    }
  return image;
}

bool same_features(const Features& a, const Features& b) {
  if (a.keypoints.size() != b.keypoints.size() || a.descriptors != b.descriptors) return false;
  for (std::size_t i = 0; i < a.keypoints.size(); ++i) {
    const Keypoint& p = a.keypoints[i];
    const Keypoint& q = b.keypoints[i];
    if (p.x != q.x || p.y != q.y || p.size != q.size || p.angle_deg != q.angle_deg ||
        p.response != q.response || p.octave != q.octave)
      return false;
  }
  return a.info.entropy_threshold_used == b.info.entropy_threshold_used &&
         a.info.blocks_kept == b.info.blocks_kept;
}

TEST(FramePipeline, StageClockChangesNoByteAndHearsEveryStage) {
  const GrayImage image = squares_image();
  for (const Mode mode : {Mode::aief, Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy}) {
    for (const bool automatic : {false, true}) {
      for (const double threshold : {1.0, 12.0}) {  // 12 bits keeps no block: the fallback runs
        ExtractorOptions options = options_for_mode(mode);
        options.n_features = 500;
        options.auto_threshold = automatic && options.entropy != EntropyMeasure::off;
        options.entropy_threshold = threshold;
        options.kernels = KernelSet::scalar;
        options.threads = 1;
        const Features expected = Extractor(options).extract(image.view());
        ASSERT_FALSE(expected.keypoints.empty());
        if (threshold == 12.0 && !options.auto_threshold &&
            options.entropy != EntropyMeasure::off) {
          EXPECT_TRUE(expected.info.threshold_lowered)
              << to_string(mode);  // the fallback's paths run
        }

        for (const int threads : {1, 2}) {
          FramePipeline pipeline(options, kernel_table(KernelSet::scalar), threads);
          StageTimes times;
          Features timed;
          pipeline.extract(image.view(), timed, &times);
          EXPECT_TRUE(same_features(expected, timed))
              << to_string(mode) << " auto " << automatic << " F " << threshold << " threads "
              << threads;
          for (const Stage stage : {Stage::pyramid, Stage::detect, Stage::select, Stage::frame})
            EXPECT_GT(times.total_ms(stage), 0.0) << static_cast<int>(stage);
          if (options.entropy != EntropyMeasure::off) {
            EXPECT_GT(times.total_ms(Stage::entropy), 0.0);
          }
          times.clear();
          for (std::size_t k = 0; k < kStageCount; ++k)
            EXPECT_EQ(times.total_ms(static_cast<Stage>(k)), 0.0);
          Features untimed;
          pipeline.extract(image.view(), untimed);  // and the sink is not kept for the next frame
          EXPECT_EQ(times.total_ms(Stage::select), 0.0);
          EXPECT_TRUE(same_features(expected, untimed));
        }
      }
    }
  }
}

TEST(StageTimes, SumsLevelsAndFrameStages) {
  StageTimes times;
  times.reserve_levels(2);
  times.add(Stage::detect, 0, 1.5);
  times.add(Stage::detect, 1, 0.5);
  times.add(Stage::detect, 1, 0.25);
  times.add(Stage::frame, -1, 2.0);
  times.reserve_levels(1);  // never shrinks
  EXPECT_DOUBLE_EQ(times.total_ms(Stage::detect), 2.25);
  EXPECT_DOUBLE_EQ(times.total_ms(Stage::frame), 2.0);
  EXPECT_DOUBLE_EQ(times.total_ms(Stage::select), 0.0);
}

}  // namespace
}  // namespace aief

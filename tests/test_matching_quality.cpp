// The matching-quality parts of the default AIEF mode (docs/design.md §11): the pixel-centre
// coordinate map, the sub-pixel peak, the candidate pool, the per-level starvation guard and the
// automatic F's indifference to uniform blocks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/extractor.hpp"
#include "core/distribution/candidate_pool.hpp"
#include "core/frame/frame_analysis.hpp"
#include "core/kernels/resize_bilinear_rows.hpp"
#include "core/level/keypoint_position.hpp"
#include "core/level/level_geometry.hpp"
#include "simd/kernels.hpp"
#include "tests/candidate_level.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using test::load_sample_gray;

TEST(SubpixelPeak, RecoversTheVertexOfASampledParabola) {
  // f(t) = 100 - 16 (t - 0.25)^2 sampled at -1, 0, 1: 75, 99, 91.
  EXPECT_FLOAT_EQ(parabola_peak_offset(75, 99, 91), 0.25f);
  EXPECT_FLOAT_EQ(parabola_peak_offset(91, 99, 75), -0.25f);
  EXPECT_FLOAT_EQ(parabola_peak_offset(10, 20, 10), 0.0f);
  // Not a strict maximum: no interior peak.
  EXPECT_FLOAT_EQ(parabola_peak_offset(20, 20, 0), 0.0f);
  EXPECT_FLOAT_EQ(parabola_peak_offset(0, 0, 0), 0.0f);
  // Every strict maximum of byte scores lands within half a pixel, towards the larger side.
  for (int peak = 1; peak < 256; peak += 7)
    for (int before = 0; before < peak; before += 5)
      for (int after = 0; after < peak; after += 3) {
        const float offset = parabola_peak_offset(before, peak, after);
        ASSERT_GT(offset, -0.5f);
        ASSERT_LT(offset, 0.5f);
        if (before > after) {
          ASSERT_LT(offset, 0.0f);
        } else if (before < after) {
          ASSERT_GT(offset, 0.0f);
        }
      }
}

// Where the pyramid really sampled level-n pixel x in level n - 1, from the resize plan's own
// taps and Q8 weights (interior pixels, where no tap is clamped), carried on to level 0 by
// linear interpolation between the taps of neighbouring pixels (the map is affine).
double sampled_source_position(const std::vector<ResizePlan>& plans, int n, double x, bool x_axis) {
  for (int k = n; k >= 1; --k) {
    const ResizePlan& plan = plans[static_cast<std::size_t>(k)];
    const auto& index = x_axis ? plan.x_index : plan.y_index;
    const auto& weight = x_axis ? plan.x_weight : plan.y_weight;
    const auto tap = [&](int i) {
      return index[static_cast<std::size_t>(i)] + weight[static_cast<std::size_t>(i)] / 256.0;
    };
    const int i = static_cast<int>(std::floor(x));
    x = tap(i) + (x - i) * (tap(i + 1) - tap(i));
  }
  return x;
}

TEST(CoordinateMap, PixelCentreMapIsWhereThePyramidSampledEveryLevel) {
  for (const auto& [width, height] :
       {std::pair{800, 640}, std::pair{853, 479}, std::pair{1000, 700}, std::pair{641, 1023}}) {
    const ExtractorOptions options;
    const std::vector<LevelGeometry> geometry = level_geometry(width, height, options);
    std::vector<ResizePlan> plans(geometry.size());
    for (std::size_t n = 1; n < geometry.size(); ++n)
      plans[n] = make_resize_plan(geometry[n - 1].width, geometry[n - 1].height, geometry[n].width,
                                  geometry[n].height);
    for (int n = 0; n < static_cast<int>(geometry.size()); ++n) {
      const LevelGeometry& level = geometry[static_cast<std::size_t>(n)];
      const LevelToImage centre = level_to_image(CoordinateMap::pixel_centre, false, level.scale,
                                                 width, height, level.width, level.height);
      const LevelToImage scaled = level_to_image(CoordinateMap::scaled, false, level.scale, width,
                                                 height, level.width, level.height);
      // Q8 weights round each level's position by <= 1/512 of a source pixel, magnified below.
      const double tolerance = 0.002 + n * 0.01 * level.scale;
      for (int x = kEdgeBorder; x < level.width - kEdgeBorder; x += 7) {
        const int y = kEdgeBorder + (x % (level.height - 2 * kEdgeBorder));
        const Candidate c = candidate_at(x, y, 50);
        const ImagePoint p = keypoint_position(c, centre);
        SCOPED_TRACE(testing::Message() << width << "x" << height << " level " << n << " at (" << x
                                        << ", " << y << ")");
        ASSERT_NEAR(p.x, sampled_source_position(plans, n, x, true), tolerance);
        ASSERT_NEAR(p.y, sampled_source_position(plans, n, y, false), tolerance);
        // The paper's map, kept by aief-paper and orbslam2, is x * scale to the bit.
        const ImagePoint q = keypoint_position(c, scaled);
        ASSERT_EQ(q.x, static_cast<float>(x) * level.scale);
        ASSERT_EQ(q.y, static_cast<float>(y) * level.scale);
      }
    }
  }
}

TEST(CoordinateMap, SubpixelOffsetMovesThePointInLevelPixels) {
  const LevelToImage mapping =
      level_to_image(CoordinateMap::pixel_centre, true, 1.2f * 1.2f, 1000, 700, 694, 486);
  Candidate c{100, 50, 99, 75, 91, 91, 75, 0};  // +0.25 in x, -0.25 in y
  const ImagePoint p = keypoint_position(c, mapping);
  EXPECT_NEAR(p.x, (100.25 + 0.5) * 1000.0 / 694.0 - 0.5, 1e-4);
  EXPECT_NEAR(p.y, (49.75 + 0.5) * 700.0 / 486.0 - 0.5, 1e-4);
}

using Level = test::CandidateLevel;

// Scores 7..18: ties at the cut-off are common.
Level make_level(const std::vector<int>& counts, std::uint32_t seed) {
  return test::make_candidate_level(counts, seed, 12);
}

TEST(CandidatePool, PoolSizeIsCeilOfPTimesTheBudget) {
  EXPECT_EQ(candidate_pool_size(std::numeric_limits<double>::infinity(), 100), -1);
  EXPECT_EQ(candidate_pool_size(1.5, 100), 150);
  EXPECT_EQ(candidate_pool_size(1.25, 3), 4);
  EXPECT_EQ(candidate_pool_size(1.0, 7), 7);
  EXPECT_EQ(candidate_pool_size(2.0, 0), 0);
  EXPECT_EQ(candidate_pool_size(1e300, 10), -1);
}

TEST(CandidatePool, KeepsTheStrongestByScoreThenPositionBlockByBlock) {
  const std::vector<std::vector<int>> layouts = {
      {0, 1, 2, 50, 50, 3, 40, 0, 9}, {10, 10, 10, 10}, {100}, {1, 1, 1, 1, 200}};
  CandidatePoolScratch scratch;
  for (std::size_t l = 0; l < layouts.size(); ++l) {
    const Level level = make_level(layouts[l], static_cast<std::uint32_t>(l) + 11);
    std::vector<std::int32_t> all;
    for (const BlockRange& block : level.blocks)
      for (std::int32_t i = block.begin; i < block.end; ++i) all.push_back(i);
    std::sort(all.begin(), all.end(), [&](std::int32_t a, std::int32_t b) {
      return stronger(level.candidates[static_cast<std::size_t>(a)],
                      level.candidates[static_cast<std::size_t>(b)]);
    });
    const std::int64_t total = static_cast<std::int64_t>(all.size());
    for (std::int64_t pool : {std::int64_t{0}, std::int64_t{1}, std::int64_t{5}, std::int64_t{23},
                              total / 2, total - 1, total, total + 4}) {
      if (pool < 0) continue;
      std::vector<Candidate> pooled;
      std::vector<std::int32_t> index;
      std::vector<BlockRange> blocks;
      pool_candidates(level.candidates, level.blocks, pool, pooled, index, blocks, scratch);
      SCOPED_TRACE(testing::Message() << "layout " << l << ", pool " << pool);
      const std::size_t expected = static_cast<std::size_t>(std::min(pool, total));
      ASSERT_EQ(pooled.size(), expected);
      ASSERT_EQ(index.size(), expected);
      // The same set as the brute force: the first `pool` by stronger().
      EXPECT_EQ(
          std::set<std::int32_t>(index.begin(), index.end()),
          std::set<std::int32_t>(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(expected)));
      // Copies of the right candidates, blocks contiguous, non-empty, in order, raster order kept.
      std::int32_t next = 0;
      for (const BlockRange& block : blocks) {
        EXPECT_EQ(block.begin, next);
        EXPECT_GT(block.size(), 0);
        next = block.end;
      }
      EXPECT_EQ(next, static_cast<std::int32_t>(expected));
      for (std::size_t i = 0; i < pooled.size(); ++i) {
        const Candidate& original = level.candidates[static_cast<std::size_t>(index[i])];
        EXPECT_EQ(pooled[i].x, original.x);
        EXPECT_EQ(pooled[i].y, original.y);
        EXPECT_EQ(pooled[i].score, original.score);
        if (i > 0) {
          EXPECT_LT(index[i - 1], index[i]);
        }
      }
    }
  }
}

std::vector<int> keypoints_per_level(const Features& features, int levels) {
  std::vector<int> count(static_cast<std::size_t>(levels), 0);
  for (const Keypoint& kp : features.keypoints) ++count[static_cast<std::size_t>(kp.octave)];
  return count;
}

// Candidates each level's blocks hold at F = 0 (every non-uniform block).
std::vector<std::int64_t> candidates_at_zero(ImageView image, const ExtractorOptions& options) {
  FrameAnalysis analysis;
  analysis.start(image, options, kernel_table(KernelSet::scalar));
  std::vector<std::int64_t> counts;
  for (int n = 0; n < analysis.level_count(); ++n) {
    analysis.build_level(n);
    analysis.compute_entropies(n);
    analysis.detect(n, 0.0);
    counts.push_back(analysis.level_candidate_count(n, 0.0));
  }
  return counts;
}

TEST(StarvationGuard, EveryLevelGetsItsBudgetWithAutoFOnATextureThatSmoothsOut) {
  // Uniform noise: fine detail that the pyramid averages away, so the coarse levels' blocks have
  // lower entropies and a frame-wide Otsu split drops them whole.
  const cv::Mat noise = test::random_image(560, 448, 7);
  ExtractorOptions options;
  options.auto_threshold = true;
  const std::vector<LevelGeometry> geometry = level_geometry(noise.cols, noise.rows, options);
  const std::vector<std::int64_t> available = candidates_at_zero(view_of(noise), options);

  ExtractorOptions paper = options_for_mode(Mode::aief_paper);
  paper.auto_threshold = true;
  const std::vector<int> paper_counts =
      keypoints_per_level(Extractor(paper).extract(view_of(noise)), options.n_levels);
  // The default mode, and its guard alone under Otsu's split (the two-class test may keep every
  // block).
  ExtractorOptions otsu_split = options;
  otsu_split.auto_requires_two_classes = false;
  const std::vector<int> counts =
      keypoints_per_level(Extractor(options).extract(view_of(noise)), options.n_levels);
  const std::vector<int> split_counts =
      keypoints_per_level(Extractor(otsu_split).extract(view_of(noise)), options.n_levels);
  int paper_starved = 0;
  for (std::size_t n = 0; n < geometry.size(); ++n) {
    SCOPED_TRACE(testing::Message() << "level " << n << ": " << available[n]
                                    << " candidates at F = 0, budget " << geometry[n].n_features);
    if (available[n] < geometry[n].n_features) continue;
    EXPECT_EQ(counts[n], geometry[n].n_features);
    EXPECT_EQ(split_counts[n], geometry[n].n_features);
    paper_starved += paper_counts[n] < geometry[n].n_features ? 1 : 0;
  }
  EXPECT_GT(paper_starved, 0)
      << "the texture no longer starves the frame-wide rule: the test proves nothing";
}

TEST(StarvationGuard, EveryLevelGetsItsBudgetAtAFixedFAboveAllBlocks) {
  const cv::Mat gray = load_sample_gray("graf", "img1.png");
  ExtractorOptions options;
  options.entropy_threshold =
      7.9;  // above every block (at most 8 bits): every level must come down
  const Features features = Extractor(options).extract(view_of(gray));
  const std::vector<LevelGeometry> geometry = level_geometry(gray.cols, gray.rows, options);
  const std::vector<int> counts = keypoints_per_level(features, options.n_levels);
  for (std::size_t n = 0; n < geometry.size(); ++n)
    EXPECT_EQ(counts[n], geometry[n].n_features) << "level " << n;
  EXPECT_TRUE(features.info.threshold_lowered);
  EXPECT_LT(features.info.entropy_threshold_used, 7.9);
  // At a threshold every level can meet, nothing is lowered.
  options.entropy_threshold = 1.0;
  EXPECT_FALSE(Extractor(options).extract(view_of(gray)).info.threshold_lowered);
}

TEST(AutoThreshold, UniformBlocksDoNotSteerTheSplit) {
  // graf inside a wide black border, as a warped image's.
  const cv::Mat gray = load_sample_gray("graf", "img1.png");
  cv::Mat framed(gray.rows + 320, gray.cols + 400, CV_8UC1, cv::Scalar(0));
  gray.copyTo(framed(cv::Rect(200, 160, gray.cols, gray.rows)));
  ExtractorOptions options;
  options.auto_threshold = true;
  // Otsu's split itself (graf alone is one class, which the two-class test would keep whole).
  options.auto_requires_two_classes = false;
  const double skipping =
      Extractor(options).extract(view_of(framed)).info.entropy_threshold_requested;
  options.auto_skips_uniform_blocks = false;
  const double counting =
      Extractor(options).extract(view_of(framed)).info.entropy_threshold_requested;
  EXPECT_LT(counting, 1.0) << "the border no longer drags Otsu down: the test proves nothing";
  EXPECT_GT(skipping, 4.0);
}

}  // namespace
}  // namespace aief

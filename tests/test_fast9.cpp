// FAST-9 scores and suppression against OpenCV's cv::FAST (nonmax on), the bit-exact oracle of
// the detector (docs/design.md §5), and against the definition of the score.
#include <algorithm>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>

#include "core/frame/frame_analysis.hpp"
#include "core/kernels/fast9_scores_row.hpp"
#include "simd/kernels.hpp"
#include "tests/fast9_whole_image.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

std::vector<FastCorner> ours(const cv::Mat& gray, int threshold) {
  std::vector<std::uint8_t> scores;
  std::vector<std::uint64_t> maxima_bits;
  std::vector<FastCorner> corners;
  fast9_whole_image(view_of(gray), threshold, kernel_table(KernelSet::scalar), scores, maxima_bits,
                    corners);
  return corners;
}

std::vector<FastCorner> opencv(const cv::Mat& gray, int threshold) {
  std::vector<cv::KeyPoint> keypoints;
  cv::FAST(gray, keypoints, threshold, true);
  std::vector<FastCorner> corners;
  for (const cv::KeyPoint& kp : keypoints)
    corners.push_back(
        {static_cast<int>(kp.pt.x), static_cast<int>(kp.pt.y), static_cast<int>(kp.response)});
  std::sort(corners.begin(), corners.end(), [](const FastCorner& a, const FastCorner& b) {
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  return corners;
}

void expect_same(const std::vector<FastCorner>& a, const std::vector<FastCorner>& b,
                 const std::string& what) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].score != b[i].score) {
      ADD_FAILURE() << what << ": corner " << i << " differs: ours (" << a[i].x << ", " << a[i].y
                    << ") score " << a[i].score << ", OpenCV (" << b[i].x << ", " << b[i].y
                    << ") score " << b[i].score;
      return;
    }
  }
  EXPECT_EQ(a.size(), b.size()) << what << ": corner counts differ";
}

TEST(Fast9, EqualsOpenCvOnRealImages) {
  for (const char* sequence : {"graf", "boat", "leuven"}) {
    const cv::Mat gray = test::load_sample_gray(sequence, "img1.png");
    for (int threshold : {7, 20, 40}) {
      const std::vector<FastCorner> expected = opencv(gray, threshold);
      ASSERT_GT(expected.size(), 100u);
      expect_same(ours(gray, threshold), expected,
                  std::string(sequence) + " t=" + std::to_string(threshold));
    }
  }
}

TEST(Fast9, EqualsOpenCvOnRandomImagesOfOddSizes) {
  std::uint32_t seed = 1;
  for (int width : {1, 3, 6, 7, 8, 9, 31, 33, 64, 65, 127, 129, 255, 257}) {
    for (int height : {1, 6, 7, 9, 37, 64}) {
      for (int kind = 0; kind < 2; ++kind) {
        const cv::Mat image = kind == 0 ? test::random_image(width, height, seed++)
                                        : test::random_textured_image(width, height, seed++);
        for (int threshold : {7, 20, 40})
          expect_same(ours(image, threshold), opencv(image, threshold),
                      std::to_string(width) + "x" + std::to_string(height) + " kind " +
                          std::to_string(kind) + " t=" + std::to_string(threshold));
      }
    }
  }
}

// The strict segment test by definition: 9 contiguous ring pixels all > p + t or all < p - t.
bool is_corner(const cv::Mat& image, int x, int y, int t) {
  const int p = image.at<std::uint8_t>(y, x);
  for (int sign : {1, -1}) {
    for (int start = 0; start < 16; ++start) {
      bool all = true;
      for (int k = 0; k < 9 && all; ++k) {
        const int i = (start + k) % 16;
        const int r = image.at<std::uint8_t>(y + kFastRingDy[i], x + kFastRingDx[i]);
        all = sign > 0 ? r > p + t : r < p - t;
      }
      if (all) return true;
    }
  }
  return false;
}

TEST(Fast9, ScoreIsTheLargestPassingThreshold) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  std::vector<std::uint8_t> scores(static_cast<std::size_t>(gray.cols));
  int checked = 0;
  for (int y = 3; y < gray.rows - 3; y += 7) {
    fast9_scores_row_scalar(gray.ptr<std::uint8_t>(y), static_cast<std::ptrdiff_t>(gray.step), 3,
                            gray.cols - 3, 1, scores.data());
    for (int x = 3; x < gray.cols - 3; ++x) {
      const int s = scores[static_cast<std::size_t>(x)];
      if (s == 0) {
        ASSERT_FALSE(is_corner(gray, x, y, 1))
            << "(" << x << ", " << y << ") is a corner at t=1 but scored 0";
        continue;
      }
      ASSERT_TRUE(is_corner(gray, x, y, s))
          << "(" << x << ", " << y << ") not a corner at its score " << s;
      ASSERT_FALSE(is_corner(gray, x, y, s + 1))
          << "(" << x << ", " << y << ") still a corner at score + 1 = " << s + 1;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(Fast9, BelowTheMinimumThresholdScoresZero) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  std::vector<std::uint8_t> low(static_cast<std::size_t>(gray.cols)),
      high(static_cast<std::size_t>(gray.cols));
  for (int y = 3; y < gray.rows - 3; y += 11) {
    const std::uint8_t* row = gray.ptr<std::uint8_t>(y);
    fast9_scores_row_scalar(row, static_cast<std::ptrdiff_t>(gray.step), 3, gray.cols - 3, 1,
                            low.data());
    fast9_scores_row_scalar(row, static_cast<std::ptrdiff_t>(gray.step), 3, gray.cols - 3, 20,
                            high.data());
    for (int x = 3; x < gray.cols - 3; ++x) {
      const int expected =
          low[static_cast<std::size_t>(x)] >= 20 ? low[static_cast<std::size_t>(x)] : 0;
      ASSERT_EQ(high[static_cast<std::size_t>(x)], expected) << "at (" << x << ", " << y << ")";
    }
  }
}

// The per-block path the pipeline runs (docs/design.md §5): the candidates of block b are the
// corners of cv::FAST(level, t, true) inside b, or of cv::FAST(level, t_min, true) when t gives
// none there (ORB-SLAM2's retry). On the real images, every level of a 3-level pyramid, several
// block sizes and threshold pairs, under every kernel set.
TEST(Fast9, PipelineBlockCandidatesEqualOpenCvWithTheRetryRule) {
  struct Setting {
    int block_size, threshold, min_threshold;
  };
  const Setting settings[] = {{8, 20, 7},   {16, 20, 7},   {32, 20, 7},
                              {64, 40, 10}, {100, 30, 30}, {37, 12, 5}};
  int retried_blocks = 0, empty_blocks = 0;
  for (const char* sequence : {"graf", "boat"}) {
    const cv::Mat gray = test::load_sample_gray(sequence, "img1.png");
    for (const Setting& setting : settings) {
      ExtractorOptions options;
      options.entropy = EntropyMeasure::off;  // every block kept
      options.n_levels = 3;
      options.block_size = setting.block_size;
      options.fast_threshold = setting.threshold;
      options.fast_min_threshold = setting.min_threshold;
      for (KernelSet set : available_kernel_sets()) {
        FrameAnalysis analysis;
        analysis.start(view_of(gray), options, kernel_table(set));
        for (int n = 0; n < analysis.level_count(); ++n) analysis.build_level(n);
        for (int n = 0; n < analysis.level_count(); ++n) {
          analysis.detect(n, 0.0);
          const PyramidLevel& level = analysis.level(n);
          const LevelBlocks& found = analysis.blocks(n);
          const cv::Mat pixels(level.pixels.height, level.pixels.width, CV_8UC1,
                               const_cast<std::uint8_t*>(level.pixels.data),
                               static_cast<std::size_t>(level.pixels.stride));
          const std::vector<FastCorner> strong = opencv(pixels, setting.threshold),
                                        weak = opencv(pixels, setting.min_threshold);
          const BlockGrid& grid = level.geometry.grid;
          // The corners of each block, found by the block edges.
          const auto by_block = [&](const std::vector<FastCorner>& corners) {
            std::vector<std::vector<FastCorner>> blocks(static_cast<std::size_t>(grid.count()));
            for (const FastCorner& c : corners) {
              if (c.x < grid.col_edges.front() || c.x >= grid.col_edges.back() ||
                  c.y < grid.row_edges.front() || c.y >= grid.row_edges.back())
                continue;
              const auto col = std::upper_bound(grid.col_edges.begin(), grid.col_edges.end(), c.x) -
                               grid.col_edges.begin() - 1;
              const auto row = std::upper_bound(grid.row_edges.begin(), grid.row_edges.end(), c.y) -
                               grid.row_edges.begin() - 1;
              blocks[static_cast<std::size_t>(row * grid.cols() + col)].push_back(c);
            }
            return blocks;
          };
          const std::vector<std::vector<FastCorner>> strong_in = by_block(strong),
                                                     weak_in = by_block(weak);
          for (int b = 0; b < grid.count(); ++b) {
            std::vector<FastCorner> expected = strong_in[static_cast<std::size_t>(b)];
            if (expected.empty()) {
              expected = weak_in[static_cast<std::size_t>(b)];
              retried_blocks += !expected.empty();
              empty_blocks += expected.empty();
            }
            std::vector<FastCorner> actual;
            const BlockRange range = found.candidate_range[static_cast<std::size_t>(b)];
            for (std::int32_t i = range.begin; i < range.end; ++i) {
              const Candidate& c = found.candidates[static_cast<std::size_t>(i)];
              actual.push_back({c.x, c.y, c.score});
            }
            const auto same = [](const FastCorner& a, const FastCorner& c) {
              return a.x == c.x && a.y == c.y && a.score == c.score;
            };
            if (actual.size() == expected.size() &&
                std::equal(actual.begin(), actual.end(), expected.begin(), same))
              continue;
            expect_same(actual, expected,
                        std::string(sequence) + " " + std::string(to_string(set)) + " level " +
                            std::to_string(n) + " block " + std::to_string(b) + " (size " +
                            std::to_string(setting.block_size) + ", t " +
                            std::to_string(setting.threshold) + "/" +
                            std::to_string(setting.min_threshold) + ")");
          }
        }
      }
    }
  }
  EXPECT_GT(retried_blocks, 0) << "no block exercised the retry at t_min";
  EXPECT_GT(empty_blocks, 0) << "no block was empty at both thresholds";
}

}  // namespace
}  // namespace aief

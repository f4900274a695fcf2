// Scale selection (ExtractorOptions::scale_selection, core/detection/scale_selection.hpp): which
// candidates are scale extrema on hand-made levels, the block ranges after the rest are removed,
// the same bytes on every kernel set and thread count, off in every mode, refused where it
// cannot act.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/detection/scale_selection.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

Candidate at(int x, int y, int score) { return candidate_at(x, y, score); }

// Level n of `levels` (each a size and its candidates) marked against its neighbours.
std::vector<std::uint8_t> marks(const std::vector<std::vector<Candidate>>& levels,
                                const std::vector<std::pair<int, int>>& sizes, int n) {
  std::vector<ScaleIndex> index(levels.size());
  for (std::size_t m = 0; m < levels.size(); ++m)
    index_candidates(levels[m], sizes[m].first, sizes[m].second, index[m]);
  const auto view = [&](int m) {
    if (m < 0 || m >= static_cast<int>(levels.size())) return ScaleLevel{};
    return ScaleLevel{&levels[static_cast<std::size_t>(m)], &index[static_cast<std::size_t>(m)]};
  };
  std::vector<std::uint8_t> keep;
  mark_scale_extrema(view(n), view(n - 1), view(n + 1), keep);
  return keep;
}

TEST(ScaleSelection, KeepsACornerOnlyOnTheLevelWhereItIsStrongest) {
  // Level 1 is level 0 halved: level-0 pixel x sits at (x + 0.5) / 2 - 0.5 on level 1.
  const std::vector<std::pair<int, int>> sizes = {{200, 100}, {100, 50}};
  const std::vector<std::vector<Candidate>> levels = {
      {at(41, 41, 30),    // level 1's (20, 20), stronger: beaten
       at(121, 41, 60),   // level 1's (60, 20), weaker: kept
       at(161, 61, 40),   // level 1's (80, 30), as strong: kept (the finer level wins a tie)
       at(101, 81, 10)},  // nothing near on level 1: kept
      {at(20, 20, 50), at(60, 20, 45), at(80, 30, 40), at(21, 41, 99)}};
  EXPECT_EQ(marks(levels, sizes, 0), (std::vector<std::uint8_t>{0, 1, 1, 1}));
  EXPECT_EQ(marks(levels, sizes, 1), (std::vector<std::uint8_t>{1, 0, 0, 1}));
}

TEST(ScaleSelection, TheWindowIsOneCoarsePixelOnEachAxis) {
  // Level 0's pixel 41 lies at 20.25 on level 1: level 1's 20 and 21 are within one pixel, 19
  // and 22 not.
  const std::vector<std::pair<int, int>> sizes = {{200, 100}, {100, 50}};
  for (int x1 = 17; x1 <= 23; ++x1) {
    const std::vector<std::vector<Candidate>> levels = {{at(41, 41, 30)}, {at(x1, 20, 50)}};
    const bool near = x1 >= 20 && x1 <= 21;
    EXPECT_EQ(marks(levels, sizes, 0)[0], near ? 0 : 1) << "level 1 x " << x1;
  }
}

TEST(ScaleSelection, RemovingCandidatesKeepsEachBlockItsOwn) {
  LevelBlocks blocks;
  blocks.reset(3);
  blocks.candidates = {at(1, 1, 9), at(2, 1, 8), at(3, 1, 7), at(4, 1, 6), at(5, 1, 5)};
  blocks.candidate_range = {{0, 2}, {2, 2}, {2, 5}};
  remove_unkept_candidates({0, 1, 1, 0, 1}, blocks);
  ASSERT_EQ(blocks.candidates.size(), 3u);
  EXPECT_EQ(blocks.candidates[0].x, 2);
  EXPECT_EQ(blocks.candidates[1].x, 3);
  EXPECT_EQ(blocks.candidates[2].x, 5);
  EXPECT_EQ(blocks.candidate_range[0].begin, 0);
  EXPECT_EQ(blocks.candidate_range[0].end, 1);
  EXPECT_EQ(blocks.candidate_range[1].begin, 1);
  EXPECT_EQ(blocks.candidate_range[1].end, 1);
  EXPECT_EQ(blocks.candidate_range[2].begin, 1);
  EXPECT_EQ(blocks.candidate_range[2].end, 3);
}

TEST(ScaleSelection, OffInEveryModeAndChangesTheKeypointsWhenOn) {
  for (const auto& mode : {Mode::aief, Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy,
                           Mode::faithful, Mode::quality})
    EXPECT_EQ(options_for_mode(mode).scale_selection, ScaleSelection::off) << to_string(mode);
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  ExtractorOptions options;
  const Features plain = Extractor(options).extract(view_of(image));
  options.scale_selection = ScaleSelection::extrema;
  const Features selected = Extractor(options).extract(view_of(image));
  EXPECT_EQ(selected.keypoints.size(), plain.keypoints.size());  // the shortfall fills the frame
  bool differs = false;
  for (std::size_t i = 0; i < plain.keypoints.size() && !differs; ++i)
    differs = std::memcmp(&plain.keypoints[i], &selected.keypoints[i], sizeof(Keypoint)) != 0;
  EXPECT_TRUE(differs);
}

TEST(ScaleSelection, RefusedWithOrbSlamCells) {
  ExtractorOptions options = options_for_mode(Mode::faithful);
  options.scale_selection = ScaleSelection::extrema;
  EXPECT_THROW(options.validate(), Error);
}

TEST(ScaleSelection, EveryKernelSetAndThreadCountGivesTheScalarBytes) {
  const std::vector<cv::Mat> images = {test::load_sample_gray("boat", "img1.png"),
                                       test::random_textured_image(203, 117, 5)};
  for (const cv::Mat& image : images)
    for (Mode mode : {Mode::aief, Mode::quality}) {
      ExtractorOptions options = options_for_mode(mode);
      options.scale_selection = ScaleSelection::extrema;
      options.kernels = KernelSet::scalar;
      options.threads = 1;
      const Features reference = Extractor(options).extract(view_of(image));
      for (KernelSet set : available_kernel_sets())
        for (int threads : {1, 2, 4}) {
          options.kernels = set;
          options.threads = threads;
          const Features other = Extractor(options).extract(view_of(image));
          ASSERT_EQ(other.keypoints.size(), reference.keypoints.size());
          for (std::size_t i = 0; i < reference.keypoints.size(); ++i) {
            ASSERT_EQ(std::memcmp(&other.keypoints[i], &reference.keypoints[i], sizeof(Keypoint)),
                      0)
                << to_string(set) << " at " << threads << " threads, keypoint " << i;
            ASSERT_EQ(other.descriptors[i], reference.descriptors[i]);
          }
        }
    }
}

}  // namespace
}  // namespace aief

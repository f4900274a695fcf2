// What a level ranks its candidates by (ExtractorOptions::candidate_ranking, docs/design.md §6):
// the FAST score of the corner pixel (the paper, ORB-SLAM2) or the score map summed over the
// corner and its four neighbours (the aief mode), in the pool and the distribution alike.
#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/distribution/candidate_pool.hpp"
#include "core/frame/frame_analysis.hpp"
#include "core/level/level_geometry.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

TEST(CandidateRanking, StrengthFirstThenScoreThenPosition) {
  Candidate lone_peak = candidate_at(10, 10, 60);      // strength 60
  Candidate broad{20, 10, 30, 20, 10, 5, 0, 35};       // strength 65: ranks above the higher peak
  Candidate same_strength{5, 30, 40, 0, 0, 0, 0, 25};  // strength 65, higher score: above `broad`
  EXPECT_TRUE(stronger(broad, lone_peak));
  EXPECT_TRUE(stronger(same_strength, broad));
  Candidate twin = broad;
  twin.x = 21;  // same strength and score: the top-left one first
  EXPECT_TRUE(stronger(broad, twin));
  EXPECT_FALSE(stronger(twin, broad));
  // With rank_extra 0 (peak_score) the order is the score's.
  broad.rank_extra = 0;
  EXPECT_TRUE(stronger(lone_peak, broad));
}

// The pool against a brute-force sort by stronger(), with strengths drawn so that equal
// strengths with different scores (and equal both) are common at the cut-off.
TEST(CandidateRanking, PoolKeepsTheStrongestByCrossStrength) {
  std::mt19937 rng(17);
  CandidatePoolScratch scratch;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Candidate> candidates;
    std::vector<BlockRange> blocks;
    const int block_count = 1 + static_cast<int>(rng() % 12);
    for (int b = 0; b < block_count; ++b) {
      const std::int32_t begin = static_cast<std::int32_t>(candidates.size());
      const int count = static_cast<int>(rng() % 30);
      std::set<std::pair<int, int>> used;
      while (static_cast<int>(used.size()) < count)
        used.insert({static_cast<int>(rng() % 32), b * 32 + static_cast<int>(rng() % 32)});
      for (const auto& [y, x] : used) {
        Candidate c = candidate_at(x, y, 7 + static_cast<int>(rng() % 6));
        c.rank_extra = static_cast<std::int32_t>(rng() % 6);
        candidates.push_back(c);
      }
      blocks.push_back({begin, static_cast<std::int32_t>(candidates.size())});
    }
    std::vector<std::int32_t> order(candidates.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::int32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
      return stronger(candidates[static_cast<std::size_t>(a)],
                      candidates[static_cast<std::size_t>(b)]);
    });
    const std::int64_t total = static_cast<std::int64_t>(candidates.size());
    for (const std::int64_t pool : {std::int64_t{1}, total / 3, total / 2, total - 1}) {
      if (pool < 1) continue;
      std::vector<Candidate> pooled;
      std::vector<std::int32_t> index;
      std::vector<BlockRange> pooled_blocks;
      pool_candidates(candidates, blocks, pool, pooled, index, pooled_blocks, scratch);
      EXPECT_EQ(
          std::set<std::int32_t>(index.begin(), index.end()),
          std::set<std::int32_t>(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(pool)))
          << "trial " << trial << ", pool " << pool << " of " << total;
    }
  }
}

// Detection fills rank_extra from the score map: the four neighbours' scores with cross_score,
// 0 with peak_score; the candidates themselves do not depend on the ranking.
TEST(CandidateRanking, DetectionCarriesTheCrossSum) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  std::vector<std::vector<Candidate>> found;
  for (const CandidateRanking ranking :
       {CandidateRanking::peak_score, CandidateRanking::cross_score}) {
    ExtractorOptions options;
    options.entropy = EntropyMeasure::off;
    options.n_levels = 3;
    options.candidate_ranking = ranking;
    FrameAnalysis analysis;
    analysis.start(view_of(gray), options, kernel_table(KernelSet::scalar));
    std::vector<Candidate> all;
    int with_neighbours = 0;
    for (int n = 0; n < analysis.level_count(); ++n) {
      analysis.build_level(n);
      analysis.detect(n, 0.0);
      for (const Candidate& c : analysis.blocks(n).candidates) {
        const int sum = c.score_left + c.score_right + c.score_up + c.score_down;
        EXPECT_EQ(c.rank_extra, ranking == CandidateRanking::cross_score ? sum : 0);
        with_neighbours += sum > 0 ? 1 : 0;
        all.push_back(c);
      }
    }
    EXPECT_GT(with_neighbours, 100);  // the neighbours' scores are really there to sum
    found.push_back(all);
  }
  ASSERT_EQ(found[0].size(), found[1].size());
  for (std::size_t i = 0; i < found[0].size(); ++i) {
    EXPECT_EQ(found[0][i].x, found[1][i].x);
    EXPECT_EQ(found[0][i].y, found[1][i].y);
    EXPECT_EQ(found[0][i].score, found[1][i].score);
  }
}

// With the pool at exactly the budget (P = 1) and no mask, a level keeps its N_n strongest
// candidates: the cross ranking reaches the output, and differs from the peak ranking.
TEST(CandidateRanking, LevelKeepsItsStrongestByTheChosenRanking) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  std::vector<std::set<std::pair<float, float>>> level0;
  for (const CandidateRanking ranking :
       {CandidateRanking::peak_score, CandidateRanking::cross_score}) {
    ExtractorOptions options;
    options.entropy = EntropyMeasure::off;
    options.candidate_pool = 1.0;
    options.subpixel = false;
    options.candidate_ranking = ranking;
    const Features features = Extractor(options).extract(view_of(gray));
    std::set<std::pair<float, float>> got;
    for (const Keypoint& kp : features.keypoints)
      if (kp.octave == 0) got.insert({kp.x, kp.y});

    FrameAnalysis analysis;
    analysis.start(view_of(gray), options, kernel_table(KernelSet::scalar));
    analysis.build_level(0);
    analysis.detect(0, 0.0);
    std::vector<Candidate> candidates = analysis.blocks(0).candidates;
    const int budget = analysis.level(0).geometry.n_features;
    ASSERT_GT(static_cast<int>(candidates.size()), budget);
    std::sort(candidates.begin(), candidates.end(), stronger);
    std::set<std::pair<float, float>> expected;
    for (int i = 0; i < budget; ++i)
      expected.insert({static_cast<float>(candidates[static_cast<std::size_t>(i)].x),
                       static_cast<float>(candidates[static_cast<std::size_t>(i)].y)});
    EXPECT_EQ(got, expected) << "ranking " << to_string(ranking);
    level0.push_back(got);
  }
  EXPECT_NE(level0[0], level0[1]);
}

TEST(CandidateRanking, ModesAndNames) {
  EXPECT_EQ(ExtractorOptions{}.candidate_ranking, CandidateRanking::cross_score);
  EXPECT_EQ(options_for_mode(Mode::aief).candidate_ranking, CandidateRanking::cross_score);
  for (const Mode mode : {Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy})
    EXPECT_EQ(options_for_mode(mode).candidate_ranking, CandidateRanking::peak_score)
        << to_string(mode);
  for (const CandidateRanking ranking :
       {CandidateRanking::peak_score, CandidateRanking::cross_score})
    EXPECT_EQ(parse_candidate_ranking(to_string(ranking)), ranking);
  EXPECT_THROW(parse_candidate_ranking("harris"), Error);
}

}  // namespace
}  // namespace aief

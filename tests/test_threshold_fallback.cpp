// The threshold fallback policy (core/entropy/threshold_fallback.hpp) on a table of block
// entropies, no image: which F each level ends at, which budgets the shortfall raises, what it
// detects.
#include <cstdint>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "aief/options.hpp"
#include "core/entropy/threshold_fallback.hpp"

namespace aief {
namespace {

// Levels of blocks, each an (entropy bits, candidates) pair; a block is kept when its entropy
// is above F (Eq. 9). Records every detection asked for.
class TableSource final : public CandidateSource {
 public:
  struct Block {
    double entropy_bits;
    std::int64_t candidates;
  };
  TableSource(std::vector<std::vector<Block>> levels, std::vector<int> budgets)
      : levels_(std::move(levels)), budgets_(std::move(budgets)) {}

  int level_count() const override { return static_cast<int>(levels_.size()); }
  int level_budget(int n) const override { return budgets_[static_cast<std::size_t>(n)]; }
  void detect_level(int n, double threshold) override {
    level_detections.push_back({n, threshold});
  }
  void detect_frame(double threshold) override { frame_detections.push_back(threshold); }
  std::int64_t level_candidates(int n, double threshold) const override {
    std::int64_t total = 0;
    for (const Block& block : levels_[static_cast<std::size_t>(n)])
      if (block.entropy_bits > threshold) total += block.candidates;
    return total;
  }

  std::vector<std::pair<int, double>> level_detections;
  std::vector<double> frame_detections;

 private:
  std::vector<std::vector<Block>> levels_;
  std::vector<int> budgets_;
};

ExtractorOptions with_guard(StarvationGuard guard, int n_features) {
  ExtractorOptions options;
  options.entropy = EntropyMeasure::histogram;
  options.starvation_guard = guard;
  options.n_features = n_features;
  return options;
}

// Level 0 is rich above F = 3; level 1 has candidates only in blocks of entropy 2.5 and 0.9.
TableSource two_levels() {
  return TableSource({{{4.0, 500}, {3.5, 200}}, {{2.5, 40}, {0.9, 100}}}, {500, 100});
}

TEST(ThresholdFallback, LevelRuleLowersOnlyTheStarvingLevelStepByStep) {
  TableSource frame = two_levels();
  const ThresholdFallback fallback(with_guard(StarvationGuard::level, 600));
  EXPECT_DOUBLE_EQ(fallback.detect_level(frame, 0, 3.0), 3.0);  // 700 >= 500 at F = 3
  ASSERT_EQ(frame.level_detections.size(), 1u);
  // Level 1: 0 at 3.0, 40 from 2.4 on, 140 from 0.8 on: eleven steps of 0.2.
  const double used = fallback.detect_level(frame, 1, 3.0);
  EXPECT_NEAR(used, 0.8, 1e-9);
  EXPECT_EQ(frame.level_detections.size(), 1u + 12u);  // the requested F, then every step
  for (std::size_t k = 2; k < frame.level_detections.size(); ++k) {
    EXPECT_EQ(frame.level_detections[k].first, 1);
    EXPECT_NEAR(frame.level_detections[k - 1].second - frame.level_detections[k].second,
                ThresholdFallback::kStep, 1e-9);
  }
}

TEST(ThresholdFallback, LevelRuleStopsAtZero) {
  TableSource frame({{{0.5, 10}}}, {100});
  const ThresholdFallback fallback(with_guard(StarvationGuard::level, 100));
  EXPECT_DOUBLE_EQ(fallback.detect_level(frame, 0, 0.5), 0.0);  // 0.5, 0.3, 0.1, then 0 (not below)
  EXPECT_EQ(frame.level_detections.back().second, 0.0);
  EXPECT_EQ(frame.level_detections.size(), 4u);
}

TEST(ThresholdFallback, LevelRuleSkipsALevelTooSmallToUse) {
  TableSource frame({{}}, {0});
  const ThresholdFallback fallback(with_guard(StarvationGuard::level, 100));
  EXPECT_DOUBLE_EQ(fallback.detect_level(frame, 0, 2.0), 2.0);
  EXPECT_EQ(frame.level_detections.size(), 1u);
}

TEST(ThresholdFallback, FrameRuleLowersEveryLevelTogether) {
  TableSource frame = two_levels();
  ThresholdFallback fallback(with_guard(StarvationGuard::frame, 740));
  // Per level nothing is lowered: detect at the requested F only.
  std::vector<double> thresholds{fallback.detect_level(frame, 0, 3.0),
                                 fallback.detect_level(frame, 1, 3.0)};
  EXPECT_EQ(thresholds, (std::vector<double>{3.0, 3.0}));
  EXPECT_EQ(frame.level_detections.size(), 2u);
  // The frame holds 700 < 740 at F = 3, 740 from F = 2.4 on (level 1's 2.5 block).
  std::vector<int> budgets{500, 100};
  EXPECT_TRUE(fallback.settle_frame(frame, 3.0, thresholds, budgets));
  EXPECT_NEAR(thresholds[0], 2.4, 1e-9);
  EXPECT_EQ(thresholds[0], thresholds[1]);
  EXPECT_EQ(frame.frame_detections.size(), 3u);      // 2.8, 2.6, 2.4
  EXPECT_EQ(budgets, (std::vector<int>{500, 100}));  // no shortfall rule in this mode
}

TEST(ThresholdFallback, FrameRuleLeavesAFedFrameAndAZeroF) {
  TableSource frame = two_levels();
  ThresholdFallback fallback(with_guard(StarvationGuard::frame, 700));
  std::vector<double> thresholds{3.0, 3.0};
  std::vector<int> budgets{500, 100};
  EXPECT_FALSE(fallback.settle_frame(frame, 3.0, thresholds, budgets));  // 700 >= 700
  ThresholdFallback starving(with_guard(StarvationGuard::frame, 10000));
  thresholds = {0.0, 0.0};
  EXPECT_FALSE(starving.settle_frame(frame, 0.0, thresholds, budgets));  // nothing left to lower
  EXPECT_TRUE(frame.frame_detections.empty());
}

TEST(ThresholdFallback, ShortfallRaisesTheFinestLevelsWithCandidatesToSpare) {
  TableSource frame = two_levels();
  ThresholdFallback fallback(with_guard(StarvationGuard::level, 600));
  std::vector<double> thresholds{3.0, 0.8};
  std::vector<int> budgets{500,
                           200};  // level 1 holds 140 at 0.8: 60 short, level 0 has 200 to spare
  EXPECT_TRUE(fallback.settle_frame(frame, 3.0, thresholds, budgets));
  EXPECT_EQ(budgets, (std::vector<int>{560, 200}));
  EXPECT_EQ(thresholds, (std::vector<double>{3.0, 0.8}));  // the level rule already chose each F
  EXPECT_TRUE(frame.frame_detections.empty());
  budgets = {500, 100};
  EXPECT_FALSE(fallback.settle_frame(frame, 3.0, thresholds, budgets));
}

TEST(ThresholdFallback, RaisedBudgetsGoToTheFinestLevelsWithCandidatesToSpare) {
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

TEST(ThresholdFallback, EntropyOffLowersNothingButHandsTheShortfallOn) {
  ExtractorOptions options = with_guard(StarvationGuard::level, 600);
  options.entropy = EntropyMeasure::off;
  // With no mask the pipeline's F is 0 and every block is kept.
  TableSource frame({{{1.0, 900}}, {{1.0, 10}}}, {500, 100});
  ThresholdFallback fallback(options);
  std::vector<double> thresholds{fallback.detect_level(frame, 0, 0.0),
                                 fallback.detect_level(frame, 1, 0.0)};
  EXPECT_EQ(thresholds, (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(frame.level_detections.size(), 2u);
  std::vector<int> budgets{500, 100};
  EXPECT_TRUE(fallback.settle_frame(frame, 0.0, thresholds, budgets));
  EXPECT_EQ(budgets, (std::vector<int>{590, 100}));
  ExtractorOptions paper = options;
  paper.starvation_guard = StarvationGuard::frame;
  ThresholdFallback frame_rule(paper);
  budgets = {500, 100};
  EXPECT_FALSE(frame_rule.settle_frame(frame, 0.0, thresholds, budgets));
}

}  // namespace
}  // namespace aief

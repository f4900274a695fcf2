// aief eval's times (tools/eval/timing.hpp): methods alternate round by round, every method at
// every position of a round equally often, and each time is the median with its spread.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tools/eval/timing.hpp"

namespace aief::eval {
namespace {

TEST(EvalTiming, EveryMethodTakesEveryPositionOfARound) {
  constexpr std::size_t methods = 4;
  for (std::size_t m = 0; m < methods; ++m) {
    std::vector<int> positions(methods, 0);
    for (std::size_t round = 0; round < methods; ++round)
      for (std::size_t slot = 0; slot < methods; ++slot)
        if (interleaved_method(methods, round, slot) == m) ++positions[slot];
    EXPECT_EQ(positions, std::vector<int>(methods, 1)) << "method " << m;
  }
}

TEST(EvalTiming, RunsEachMethodOncePerRoundAlternating) {
  std::string order;
  const std::vector<std::function<void()>> work = {[&] { order += 'a'; }, [&] { order += 'b'; },
                                                   [&] { order += 'c'; }};
  const std::vector<MethodTimes> times = time_interleaved(work, 3);
  EXPECT_EQ(order, "abcbcacab");
  ASSERT_EQ(times.size(), 3u);
  for (const MethodTimes& method : times)
    for (const TimeSpread& t : {method.cpu, method.wall}) {
      EXPECT_EQ(t.runs, 3);
      EXPECT_LE(t.min_ms, t.median_ms);
      EXPECT_LE(t.median_ms, t.max_ms);
    }
}

TEST(EvalTiming, MedianAndSpread) {
  const TimeSpread odd = spread_of({9, 1, 5});
  EXPECT_DOUBLE_EQ(odd.median_ms, 5);
  EXPECT_DOUBLE_EQ(odd.min_ms, 1);
  EXPECT_DOUBLE_EQ(odd.max_ms, 9);
  EXPECT_DOUBLE_EQ(spread_of({4, 1, 2, 3}).median_ms, 2.5);
  EXPECT_EQ(spread_of({}).runs, 0);
}

}  // namespace
}  // namespace aief::eval

// Brute-force Hamming matching: against a naive loop, each filter by its definition.
#include <random>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "core/kernels/hamming_256_many.hpp"

namespace aief {
namespace {

std::vector<Descriptor> random_descriptors(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<Descriptor> out(static_cast<std::size_t>(n));
  for (Descriptor& d : out)
    for (std::uint8_t& byte : d) byte = static_cast<std::uint8_t>(rng());
  return out;
}

// b = a shuffled with a few bits flipped, plus distractors: most queries have a true partner.
void make_pair(int n, std::uint32_t seed, std::vector<Descriptor>& a, std::vector<Descriptor>& b) {
  std::mt19937 rng(seed);
  a = random_descriptors(n, seed);
  b = a;
  for (Descriptor& d : b)
    for (int flip = 0; flip < 20; ++flip)
      d[rng() % 32] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
  std::shuffle(b.begin(), b.end(), rng);
  const std::vector<Descriptor> extra = random_descriptors(n / 3, seed + 1);
  b.insert(b.end(), extra.begin(), extra.end());
}

int distance(const Descriptor& x, const Descriptor& y) {
  return static_cast<int>(hamming_256_scalar(x.data(), y.data()));
}

int nearest(const Descriptor& q, const std::vector<Descriptor>& set) {
  int best = 0;
  for (int j = 1; j < static_cast<int>(set.size()); ++j)
    if (distance(q, set[static_cast<std::size_t>(j)]) <
        distance(q, set[static_cast<std::size_t>(best)]))
      best = j;
  return best;
}

TEST(Matcher, MutualEqualsANaiveCrossCheck) {
  std::vector<Descriptor> a, b;
  make_pair(300, 3, a, b);
  const std::vector<Match> matches = match_descriptors(a, b);
  std::vector<Match> expected;
  for (int i = 0; i < static_cast<int>(a.size()); ++i) {
    const int j = nearest(a[static_cast<std::size_t>(i)], b);
    if (nearest(b[static_cast<std::size_t>(j)], a) == i)
      expected.push_back(
          {i, j, distance(a[static_cast<std::size_t>(i)], b[static_cast<std::size_t>(j)])});
  }
  ASSERT_EQ(matches.size(), expected.size());
  for (std::size_t k = 0; k < matches.size(); ++k) {
    EXPECT_EQ(matches[k].query, expected[k].query);
    EXPECT_EQ(matches[k].train, expected[k].train);
    EXPECT_EQ(matches[k].distance, expected[k].distance);
  }
  EXPECT_GT(matches.size(), 250u);
}

TEST(Matcher, RatioAndPaperFiltersByTheirDefinitions) {
  std::vector<Descriptor> a, b;
  make_pair(200, 5, a, b);
  std::vector<Descriptor> noise = random_descriptors(100, 11);
  a.insert(a.end(), noise.begin(), noise.end());
  MatchOptions ratio;
  ratio.kind = MatcherKind::ratio;
  ratio.ratio = 0.7;
  MatchOptions paper;
  paper.kind = MatcherKind::paper;
  const std::vector<Match> by_ratio = match_descriptors(a, b, ratio);
  const std::vector<Match> by_paper = match_descriptors(a, b, paper);
  int min_distance = 256;
  for (const Descriptor& q : a)
    min_distance = std::min(min_distance, distance(q, b[static_cast<std::size_t>(nearest(q, b))]));
  std::size_t r = 0, p = 0;
  for (int i = 0; i < static_cast<int>(a.size()); ++i) {
    std::vector<int> d;
    for (const Descriptor& t : b) d.push_back(distance(a[static_cast<std::size_t>(i)], t));
    std::vector<int> sorted = d;
    std::sort(sorted.begin(), sorted.end());
    const bool passes_ratio = sorted[0] < 0.7 * sorted[1];
    ASSERT_EQ(r < by_ratio.size() && by_ratio[r].query == i, passes_ratio) << "query " << i;
    if (passes_ratio) ++r;
    const bool passes_paper = sorted[0] <= std::max(2 * min_distance, 30);
    ASSERT_EQ(p < by_paper.size() && by_paper[p].query == i, passes_paper) << "query " << i;
    if (passes_paper) ++p;
  }
  EXPECT_GT(by_ratio.size(), 150u);
  EXPECT_LT(by_ratio.size(), a.size());
}

TEST(Matcher, EmptyInputsAndBadOptions) {
  const std::vector<Descriptor> some = random_descriptors(5, 1), none;
  EXPECT_TRUE(match_descriptors(none, some).empty());
  EXPECT_TRUE(match_descriptors(some, none).empty());
  MatchOptions bad;
  bad.ratio = 1.5;
  EXPECT_THROW(match_descriptors(some, some, bad), Error);
  bad = {};
  bad.max_distance = -1;
  EXPECT_THROW(match_descriptors(some, some, bad), Error);
  EXPECT_THROW(parse_matcher_kind("flann"), Error);
}

TEST(Matcher, TiesGoToTheLowestIndex) {
  std::vector<Descriptor> a = random_descriptors(1, 9);
  std::vector<Descriptor> b = {a[0], a[0], a[0]};
  const std::vector<Match> matches = match_descriptors(a, b);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].train, 0);
}

}  // namespace
}  // namespace aief

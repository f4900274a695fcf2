// Brute-force Hamming matching: against a naive loop, each filter by its definition.
#include <algorithm>
#include <iterator>
#include <random>
#include <utility>

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

// `base` with bits [first, first + count) flipped: at exactly `count` bits from it.
Descriptor flipped(Descriptor base, int first, int count) {
  for (int bit = first; bit < first + count; ++bit)
    base[static_cast<std::size_t>(bit / 8)] ^= static_cast<std::uint8_t>(1u << (bit % 8));
  return base;
}

std::vector<std::pair<int, int>> pairs_of(const std::vector<Match>& matches) {
  std::vector<std::pair<int, int>> pairs;
  for (const Match& m : matches) pairs.emplace_back(m.query, m.train);
  return pairs;
}

MatchOptions with_kind(MatcherKind kind, double ratio = 0.8) {
  MatchOptions options;
  options.kind = kind;
  options.ratio = ratio;
  return options;
}

// Two random bases are ~128 bits apart; every distance that matters here is set by flipped bits.
// Query 0: nearest train 0 at 10, train 1 at 12 (10 < 0.8 x 12 fails), train 0's nearest query
// is 0: mutual keeps it, ratio drops it. Query 1: train 2 at 15, nothing else near: ratio keeps
// it, but train 2's nearest query is 2 (at 5): mutual drops it. Query 2 passes both.
TEST(Matcher, MutualRatioKeepsExactlyWhatBothKeep) {
  const std::vector<Descriptor> bases = random_descriptors(2, 21);
  const Descriptor& x = bases[0];
  const Descriptor& y = bases[1];
  const std::vector<Descriptor> a = {x, flipped(y, 0, 20), y};
  const std::vector<Descriptor> b = {flipped(x, 0, 10), flipped(x, 100, 12), flipped(y, 0, 5)};
  using Pairs = std::vector<std::pair<int, int>>;
  EXPECT_EQ(pairs_of(match_descriptors(a, b, with_kind(MatcherKind::mutual))),
            (Pairs{{0, 0}, {2, 2}}));
  EXPECT_EQ(pairs_of(match_descriptors(a, b, with_kind(MatcherKind::ratio))),
            (Pairs{{1, 2}, {2, 2}}));
  const std::vector<Match> both = match_descriptors(a, b, with_kind(MatcherKind::mutual_ratio));
  ASSERT_EQ(pairs_of(both), (Pairs{{2, 2}}));
  EXPECT_EQ(both[0].distance, 5);
  // A ratio that lets query 0 through (10 < 0.9 x 12): mutual_ratio follows --ratio.
  EXPECT_EQ(pairs_of(match_descriptors(a, b, with_kind(MatcherKind::mutual_ratio, 0.9))),
            (Pairs{{0, 0}, {2, 2}}));
}

TEST(Matcher, MutualRatioEqualsABruteForceOracle) {
  for (std::uint32_t seed : {7u, 8u}) {
    std::vector<Descriptor> a, b;
    make_pair(200, seed, a, b);
    const std::vector<Descriptor> noise = random_descriptors(80, seed + 40);
    a.insert(a.end(), noise.begin(), noise.end());
    // Near copies of 30 queries (ratio passes, mutual fails: the original is nearer) and of 30
    // trains (mutual passes, ratio fails: two trains almost equally near).
    for (int k = 0; k < 30; ++k) {
      a.push_back(flipped(a[static_cast<std::size_t>(k)], 100, 30));
      b.push_back(flipped(b[static_cast<std::size_t>(k)], 200, 4));
    }
    const std::vector<Match> matches =
        match_descriptors(a, b, with_kind(MatcherKind::mutual_ratio));
    std::vector<Match> expected;
    for (int i = 0; i < static_cast<int>(a.size()); ++i) {
      const Descriptor& q = a[static_cast<std::size_t>(i)];
      const int j = nearest(q, b);
      std::vector<int> d;
      for (const Descriptor& t : b) d.push_back(distance(q, t));
      std::sort(d.begin(), d.end());
      if (d[0] < 0.8 * d[1] && nearest(b[static_cast<std::size_t>(j)], a) == i)
        expected.push_back({i, j, d[0]});
    }
    ASSERT_EQ(matches.size(), expected.size()) << "seed " << seed;
    for (std::size_t k = 0; k < matches.size(); ++k) {
      EXPECT_EQ(matches[k].query, expected[k].query);
      EXPECT_EQ(matches[k].train, expected[k].train);
      EXPECT_EQ(matches[k].distance, expected[k].distance);
    }
    // The intersection of the two filters, and strictly smaller than each on this data.
    const std::vector<Match> mutual = match_descriptors(a, b, with_kind(MatcherKind::mutual));
    const std::vector<Match> ratio = match_descriptors(a, b, with_kind(MatcherKind::ratio));
    std::vector<std::pair<int, int>> intersection;
    const auto m = pairs_of(mutual), r = pairs_of(ratio);
    std::set_intersection(m.begin(), m.end(), r.begin(), r.end(), std::back_inserter(intersection));
    EXPECT_EQ(pairs_of(matches), intersection);
    EXPECT_LT(matches.size(), mutual.size());
    EXPECT_LT(matches.size(), ratio.size());
    EXPECT_GT(matches.size(), 50u);
  }
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
  EXPECT_EQ(parse_matcher_kind("mutual_ratio"), MatcherKind::mutual_ratio);
  EXPECT_EQ(to_string(MatcherKind::mutual_ratio), "mutual_ratio");
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

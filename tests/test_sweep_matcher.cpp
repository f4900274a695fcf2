// The sweep's incremental matcher: at every call the same matches as match_descriptors, on data
// full of ties and duplicates, through sets that change a little, a lot, to nothing, and out of
// order; and on the real sweep of every bundled pair.
#include <random>

#include <gtest/gtest.h>

#include "aief/match.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/match/matcher.hpp"
#include "core/sweep/adaptive_sweep.hpp"
#include "core/sweep/sweep_matcher.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

// Bytes from {0x00, 0x0f, 0xff}: distances are multiples of 4 from a few values, so nearest and
// second nearest tie all the time; every fifth descriptor repeats an earlier one.
std::vector<Descriptor> tied_pool(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  static constexpr std::uint8_t kBytes[3] = {0x00, 0x0f, 0xff};
  std::vector<Descriptor> pool(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < pool.size(); ++i) {
    if (i >= 5 && i % 5 == 0) {
      pool[i] = pool[rng() % i];
      continue;
    }
    for (std::uint8_t& byte : pool[i]) byte = kBytes[rng() % 3];
  }
  return pool;
}

struct Selection {
  std::vector<std::int32_t> ids;
  std::vector<Descriptor> descriptors;
};

Selection select_ids(const std::vector<Descriptor>& pool, const std::vector<std::int32_t>& ids) {
  Selection s;
  s.ids = ids;
  for (std::int32_t id : ids) s.descriptors.push_back(pool[static_cast<std::size_t>(id)]);
  return s;
}

// Next set: each id of the pool toggled with probability `churn`, ascending; sometimes shuffled.
std::vector<std::int32_t> next_ids(const std::vector<std::int32_t>& ids, int pool_size,
                                   double churn, bool shuffle, std::mt19937& rng) {
  std::vector<std::uint8_t> in(static_cast<std::size_t>(pool_size), 0);
  for (std::int32_t id : ids) in[static_cast<std::size_t>(id)] = 1;
  std::bernoulli_distribution toggle(churn);
  std::vector<std::int32_t> out;
  for (int id = 0; id < pool_size; ++id) {
    if (toggle(rng)) in[static_cast<std::size_t>(id)] ^= 1;
    if (in[static_cast<std::size_t>(id)]) out.push_back(id);
  }
  if (shuffle) std::shuffle(out.begin(), out.end(), rng);
  return out;
}

void expect_same(const std::vector<Match>& expected, const std::vector<Match>& actual,
                 const std::string& where) {
  ASSERT_EQ(expected.size(), actual.size()) << where;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    ASSERT_EQ(expected[k].query, actual[k].query) << where << " match " << k;
    ASSERT_EQ(expected[k].train, actual[k].train) << where << " match " << k;
    ASSERT_EQ(expected[k].distance, actual[k].distance) << where << " match " << k;
  }
}

std::vector<MatchOptions> every_rule() {
  std::vector<MatchOptions> rules;
  for (MatcherKind kind :
       {MatcherKind::mutual, MatcherKind::ratio, MatcherKind::paper, MatcherKind::mutual_ratio})
    for (int max_distance : {256, 60}) {
      MatchOptions options;
      options.kind = kind;
      options.max_distance = max_distance;
      rules.push_back(options);
    }
  MatchOptions ratio_one;  // second == best passes no ratio test; ties decide everything
  ratio_one.kind = MatcherKind::ratio;
  ratio_one.ratio = 1.0;
  rules.push_back(ratio_one);
  return rules;
}

TEST(NeighbourList, HoldsAnExactPrefixOfTheOtherSet) {
  NeighbourList list;
  constexpr int kOffered = NeighbourList::kLength + 2;
  for (int k = kOffered - 1; k >= 0; --k) list.offer({100 + k, k});  // each closer than the last
  ASSERT_EQ(list.count, NeighbourList::kLength);
  EXPECT_FALSE(list.complete) << "the two farthest fell off";
  for (int k = 0; k < list.count; ++k)
    EXPECT_EQ(list.entries[static_cast<std::size_t>(k)].index, k);
  list.offer({100 + kOffered, kOffered});  // past the last entry: unknown territory, not kept
  EXPECT_EQ(list.entries[static_cast<std::size_t>(list.count - 1)].index,
            NeighbourList::kLength - 1);
  list.offer({100, 99});  // ties to the lower index: after element 0
  EXPECT_EQ(list.entries[1].index, 99);

  // Every neighbour leaves but one: the list still knows the nearest, not the second nearest.
  std::vector<std::int32_t> new_index_of_old(100, -1);
  new_index_of_old[99] = 0;
  list.renumber(new_index_of_old);
  EXPECT_EQ(list.count, 1);
  EXPECT_TRUE(list.knows(1));
  EXPECT_FALSE(list.knows(2));
  std::fill(new_index_of_old.begin(), new_index_of_old.end(), -1);
  list.renumber(new_index_of_old);
  EXPECT_FALSE(list.knows(1));
  list.offer({0, 0});  // an incomplete empty list cannot tell where a newcomer ranks
  EXPECT_EQ(list.count, 0);

  NeighbourList whole;  // a complete list of a small set stays complete
  whole.offer({5, 1});
  whole.offer({5, 0});
  EXPECT_TRUE(whole.complete);
  EXPECT_TRUE(whole.knows(3));
  EXPECT_EQ(whole.entries[0].index, 0);
}

// Under every kernel set (the blocked Hamming and the bound filter are kernels), against the
// scalar brute force.
TEST(SweepMatcher, EqualsBruteForceOnTiedRandomSetsThatChange) {
  const KernelTable& scalar = kernel_table(KernelSet::scalar);
  const int pool_size = 300;
  const std::vector<Descriptor> pool_a = tied_pool(pool_size, 1), pool_b = tied_pool(pool_size, 2);
  for (KernelSet set : available_kernel_sets()) {
    for (const MatchOptions& rule : every_rule()) {
      std::mt19937 rng(7);
      SweepMatcher matcher(rule, kernel_table(set));
      std::vector<std::int32_t> ids_a, ids_b;
      for (int call = 0; call < 60; ++call) {
        // Mostly small steps (the sweep's), some large ones that empty the lists, an empty set,
        // and a call whose order changed.
        const double churn = call % 10 == 9 ? 0.5 : 0.03;
        const bool shuffle = call == 31;
        ids_a = call == 20 ? std::vector<std::int32_t>{}
                           : next_ids(ids_a, pool_size, call == 0 ? 0.6 : churn, shuffle, rng);
        ids_b = call == 40 ? std::vector<std::int32_t>{0}
                           : next_ids(ids_b, pool_size, call == 0 ? 0.6 : churn, false, rng);
        const Selection a = select_ids(pool_a, ids_a), b = select_ids(pool_b, ids_b);
        const std::vector<Match> expected =
            match_descriptors(a.descriptors, b.descriptors, rule, scalar);
        const std::vector<Match> actual = matcher.match(a.descriptors, a.ids, b.descriptors, b.ids);
        expect_same(expected, actual,
                    std::string(to_string(set)) + " kind " + std::string(to_string(rule.kind)) +
                        " max_distance " + std::to_string(rule.max_distance) + " call " +
                        std::to_string(call));
      }
    }
  }
}

TEST(SweepMatcher, EqualsBruteForceAtEveryThresholdOfTheBundledPairs) {
  const KernelTable& kernels = kernel_table(KernelSet::auto_select);
  for (const char* sequence : {"graf", "boat", "leuven"}) {
    const cv::Mat a = test::load_sample_gray(sequence, "img1.png");
    const cv::Mat b = test::load_sample_gray(sequence, "img2.png");
    const SweepFeatures sweep =
        sweep_features(view_of(a), view_of(b), ExtractorOptions{}, SweepOptions{}, kernels);
    ASSERT_GT(sweep.a.size(), 10u);
    for (const MatchOptions& rule : every_rule()) {
      SweepMatcher matcher(rule, kernels);
      long long brute_force_distances = 0;
      for (std::size_t c = 0; c < sweep.a.size(); ++c) {
        const ThresholdFeatures &fa = sweep.a[c], &fb = sweep.b[c];
        const std::vector<Match> expected =
            match_descriptors(fa.features.descriptors, fb.features.descriptors, rule, kernels);
        const std::vector<Match> actual =
            matcher.match(fa.features.descriptors, fa.ids, fb.features.descriptors, fb.ids);
        expect_same(expected, actual,
                    std::string(sequence) + " threshold " + std::to_string(c) + " kind " +
                        std::string(to_string(rule.kind)));
        brute_force_distances +=
            static_cast<long long>(fa.ids.size()) * static_cast<long long>(fb.ids.size());
      }
      // The point of it: most distances are reused (the sweep itself skips repeated thresholds).
      EXPECT_LT(matcher.distances_computed(), brute_force_distances / 4) << sequence;
    }
  }
}

}  // namespace
}  // namespace aief

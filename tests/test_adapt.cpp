// The adaptive sweep: its choice rule, its curve, and the proof that it reuses everything that
// does not depend on F (kernel calls counted; each threshold equal to an independent extraction).
#include <atomic>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/level/level_geometry.hpp"
#include "core/sweep/adaptive_sweep.hpp"
#include "core/sweep/sweep_runs.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using test::load_sample_gray;
using test::same_bytes;

// Scalar kernels that count their work.
struct Counts {
  std::atomic<long long> resized_rows{0}, blurred_rows{0}, histogram_pixels{0}, scored_pixels{0},
      oriented{0}, described{0};
} counts;

KernelTable counting_kernels() {
  KernelTable table;
  table.name = "counting";
  table.resize_bilinear_rows = [](ImageView src, const ResizePlan& plan, MutableImageView dst,
                                  int y0, int y1) {
    counts.resized_rows += y1 - y0;
    resize_bilinear_rows_scalar(src, plan, dst, y0, y1);
  };
  table.gaussian7_rows = [](ImageView src, MutableImageView dst, int y0, int y1, int x0, int x1) {
    counts.blurred_rows += y1 - y0;
    gaussian7_rows_scalar(src, dst, y0, y1, x0, x1);
  };
  table.accumulate_histogram = [](const std::uint8_t* data, std::ptrdiff_t stride, int w, int h,
                                  std::uint32_t* hist) {
    counts.histogram_pixels += static_cast<long long>(w) * h;
    accumulate_histogram_scalar(data, stride, w, h, hist);
  };
  table.fast9_scores_row = [](const std::uint8_t* row, std::ptrdiff_t stride, int x0, int x1, int t,
                              std::uint8_t* scores) {
    counts.scored_pixels += x1 - x0;
    fast9_scores_row_scalar(row, stride, x0, x1, t, scores);
  };
  table.ic_moments = [](ImageView level, const PixelPoint* points, int n, std::int32_t* m10,
                        std::int32_t* m01) {
    counts.oriented += n;
    ic_moments_scalar(level, points, n, m10, m01);
  };
  table.rbrief_describe = [](ImageView blurred, const PixelPoint* points, const float* angles,
                             int n, std::uint8_t* out) {
    counts.described += n;
    rbrief_describe_scalar(blurred, points, angles, n, out);
  };
  return table;
}

TEST(AdaptiveSweep, ChoosesTheBestEligibleThresholdOfItsCurve) {
  const cv::Mat a = load_sample_gray("graf", "img1.png");
  const cv::Mat b = load_sample_gray("graf", "img2.png");
  const SweepOptions sweep;
  const AdaptResult result = adapt(view_of(a), view_of(b), {}, sweep);
  ASSERT_TRUE(result.found);
  const int expected_cycles = static_cast<int>(std::ceil(result.image_entropy_bits / sweep.step));
  ASSERT_EQ(static_cast<int>(result.curve.size()), expected_cycles);
  const SweepPoint& chosen = result.curve[static_cast<std::size_t>(result.chosen_index)];
  EXPECT_DOUBLE_EQ(result.threshold, chosen.threshold);
  EXPECT_GE(chosen.inliers, sweep.min_inliers);
  for (std::size_t i = 0; i < result.curve.size(); ++i) {
    const SweepPoint& point = result.curve[i];
    EXPECT_NEAR(point.threshold, sweep.step * static_cast<double>(i), 1e-9);
    if (i > 0) {
      EXPECT_LE(point.kept_blocks, result.curve[i - 1].kept_blocks)
          << "the mask only shrinks as F grows";
    }
    if (point.putative > 0) {
      EXPECT_DOUBLE_EQ(point.cmr, static_cast<double>(point.inliers) / point.putative);
    }
    if (!point.eligible) continue;
    EXPECT_TRUE(point.cmr < chosen.cmr ||
                (point.cmr == chosen.cmr && point.inliers <= chosen.inliers))
        << "threshold " << point.threshold << " beats the chosen " << chosen.threshold;
  }
  EXPECT_EQ(static_cast<int>(result.features_a.keypoints.size()), chosen.keypoints_a);
  EXPECT_EQ(static_cast<int>(result.matches.size()), chosen.putative);
  // The sweep matches through one distance matrix: the same matches as matching directly.
  const std::vector<Match> direct =
      match_descriptors(result.features_a.descriptors, result.features_b.descriptors, sweep.match);
  ASSERT_EQ(direct.size(), result.matches.size());
  for (std::size_t k = 0; k < direct.size(); ++k) {
    EXPECT_EQ(direct[k].query, result.matches[k].query);
    EXPECT_EQ(direct[k].train, result.matches[k].train);
    EXPECT_EQ(direct[k].distance, result.matches[k].distance);
  }
  EXPECT_EQ(result.homography.inliers, chosen.inliers);
}

TEST(AdaptiveSweep, EachThresholdEqualsAnIndependentExtraction) {
  const cv::Mat a = load_sample_gray("boat", "img1.png");
  const cv::Mat b = load_sample_gray("boat", "img2.png");
  SweepOptions sweep;
  sweep.step = 0.8;  // fewer thresholds, same code path
  const AdaptResult result = adapt(view_of(a), view_of(b), {}, sweep);
  int compared = 0;
  for (const SweepPoint& point : result.curve) {
    ExtractorOptions options;
    options.entropy_threshold = point.threshold;
    const Features independent = extract(view_of(a), options);
    if (independent.info.threshold_lowered) continue;  // the single-frame rule changed F
    EXPECT_EQ(static_cast<int>(independent.keypoints.size()), point.keypoints_a)
        << "F = " << point.threshold;
    EXPECT_EQ(independent.info.blocks_kept, point.kept_blocks) << "F = " << point.threshold;
    ++compared;
  }
  EXPECT_GE(compared, 3);
  ExtractorOptions at_chosen;
  at_chosen.entropy_threshold = result.threshold;
  const Features chosen_a = extract(view_of(a), at_chosen);
  if (!chosen_a.info.threshold_lowered) {
    EXPECT_TRUE(same_bytes(chosen_a, result.features_a));
  }
}

TEST(AdaptiveSweep, ReadsEveryPixelOnceWhateverTheNumberOfThresholds) {
  const cv::Mat a = load_sample_gray("graf", "img1.png");
  const cv::Mat b = load_sample_gray("graf", "img2.png");
  const KernelTable kernels = counting_kernels();
  const auto run = [&](double step) {
    counts.resized_rows = counts.blurred_rows = counts.histogram_pixels = counts.scored_pixels = 0;
    counts.oriented = counts.described = 0;
    SweepOptions sweep;
    sweep.step = step;
    return adapt_with_kernels(view_of(a), view_of(b), ExtractorOptions{}, sweep, kernels);
  };
  const AdaptResult coarse = run(2.0);
  const long long coarse_scored = counts.scored_pixels, coarse_hist = counts.histogram_pixels;
  const long long coarse_resized = counts.resized_rows;
  const AdaptResult fine = run(0.2);
  ASSERT_GT(fine.curve.size(), 5 * coarse.curve.size());
  // Pixel kernels: the same work for 4 thresholds as for 40.
  EXPECT_EQ(counts.scored_pixels, coarse_scored);
  EXPECT_EQ(counts.histogram_pixels, coarse_hist);
  EXPECT_EQ(counts.resized_rows, coarse_resized);
  // Histograms: each pixel of level 0 once (blocks and border strips), each block pixel of the
  // other levels once. Blur: each usable level at most once per image.
  long long expected_histogram = 0, level_rows = 0;
  for (const cv::Mat* image : {&a, &b}) {
    const std::vector<LevelGeometry> levels =
        level_geometry(image->cols, image->rows, ExtractorOptions{});
    for (std::size_t n = 0; n < levels.size(); ++n) {
      if (levels[n].grid.count() == 0) continue;
      level_rows += levels[n].height;
      expected_histogram += n == 0 ? static_cast<long long>(image->total())
                                   : static_cast<long long>(levels[n].width - 2 * kEdgeBorder) *
                                         (levels[n].height - 2 * kEdgeBorder);
    }
  }
  EXPECT_EQ(counts.histogram_pixels, expected_histogram);
  EXPECT_LE(counts.blurred_rows, level_rows);
  EXPECT_EQ(counts.oriented, counts.described);
  long long distinct_upper_bound = 0;
  for (const SweepPoint& point : fine.curve)
    distinct_upper_bound =
        std::max<long long>(distinct_upper_bound, point.keypoints_a + point.keypoints_b);
  EXPECT_LE(counts.described, 4 * distinct_upper_bound) << "descriptors recomputed per threshold";
}

bool same_result(const AdaptResult& x, const AdaptResult& y) {
  if (x.found != y.found || x.threshold != y.threshold || x.chosen_index != y.chosen_index ||
      x.curve.size() != y.curve.size())
    return false;
  for (std::size_t i = 0; i < x.curve.size(); ++i) {
    const SweepPoint &p = x.curve[i], &q = y.curve[i];
    if (p.threshold != q.threshold || p.kept_blocks != q.kept_blocks ||
        p.kept_blocks_b != q.kept_blocks_b || p.keypoints_a != q.keypoints_a ||
        p.keypoints_b != q.keypoints_b || p.putative != q.putative || p.inliers != q.inliers ||
        p.cmr != q.cmr || p.eligible != q.eligible)
      return false;
  }
  if (!same_bytes(x.features_a, y.features_a) || !same_bytes(x.features_b, y.features_b))
    return false;
  if (x.matches.size() != y.matches.size()) return false;
  for (std::size_t k = 0; k < x.matches.size(); ++k)
    if (x.matches[k].query != y.matches[k].query || x.matches[k].train != y.matches[k].train ||
        x.matches[k].distance != y.matches[k].distance)
      return false;
  return x.homography.found == y.homography.found && x.homography.H == y.homography.H &&
         x.homography.inlier_mask == y.homography.inlier_mask &&
         x.homography.inliers == y.homography.inliers;
}

// One AdaptiveSweep run on pair after pair (two sizes, back and forth) answers each pair as a
// fresh sweep does, under every kernel set and at one and two threads: nothing of one pair
// leaks into the next, and the thread count changes nothing.
TEST(AdaptiveSweep, ReusedOverPairsEqualsAFreshSweepAtEveryKernelSetAndThreadCount) {
  const cv::Mat graf1 = load_sample_gray("graf", "img1.png"),
                graf2 = load_sample_gray("graf", "img2.png");
  const cv::Mat boat1 = load_sample_gray("boat", "img1.png"),
                boat2 = load_sample_gray("boat", "img2.png");
  SweepOptions sweep;
  sweep.step = 0.8;  // a quarter of the thresholds (10 on graf), same code paths
  ExtractorOptions reference;
  reference.kernels = KernelSet::scalar;
  reference.threads = 1;
  const AdaptResult graf = adapt(view_of(graf1), view_of(graf2), reference, sweep);
  const AdaptResult boat = adapt(view_of(boat1), view_of(boat2), reference, sweep);
  ASSERT_TRUE(graf.found);
  ASSERT_TRUE(boat.found);
  for (KernelSet set : available_kernel_sets()) {
    for (int threads : {1, 2}) {
      ExtractorOptions options;
      options.kernels = set;
      options.threads = threads;
      AdaptiveSweep reused(options, sweep);
      AdaptResult result;
      const std::string where = std::string(to_string(set)) + " threads " + std::to_string(threads);
      reused.run(view_of(graf1), view_of(graf2), result);
      EXPECT_TRUE(same_result(graf, result)) << where << " graf, first pair";
      reused.run(view_of(boat1), view_of(boat2), result);
      EXPECT_TRUE(same_result(boat, result)) << where << " boat after graf";
      reused.run(view_of(graf1), view_of(graf2), result);
      EXPECT_TRUE(same_result(graf, result)) << where << " graf after boat";
    }
  }
}

double largest_run_cost(const std::vector<double>& fresh, const std::vector<double>& incremental,
                        const std::vector<int>& begin) {
  double largest = 0;
  for (std::size_t r = 0; r + 1 < begin.size(); ++r) {
    double cost = fresh[static_cast<std::size_t>(begin[r])];
    for (int k = begin[r] + 1; k < begin[r + 1]; ++k)
      cost += incremental[static_cast<std::size_t>(k)];
    largest = std::max(largest, cost);
  }
  return largest;
}

TEST(BalancedRuns, CutsWhereTheWorkIsEvenNotTheCount) {
  // Thresholds 0-1 are expensive to reach, 2-5 cheap: an even count would give run 0 the bulk.
  const std::vector<double> fresh = {100, 100, 100, 100, 100, 100};
  const std::vector<double> incremental = {0, 90, 5, 5, 5, 5};
  const std::vector<int> begin = balanced_runs(fresh, incremental, 2);
  EXPECT_EQ(begin, (std::vector<int>{0, 1, 6}));
  EXPECT_EQ(largest_run_cost(fresh, incremental, begin), 120);
}

TEST(BalancedRuns, EqualsTheBestOfEveryCutOnRandomCosts) {
  std::uint64_t state = 7;
  const auto next = [&] {
    return static_cast<double>((state = state * 6364136223846793005ull + 1442695040888963407ull) >>
                               54);
  };
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 9;
    std::vector<double> fresh(static_cast<std::size_t>(n)),
        incremental(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      incremental[static_cast<std::size_t>(k)] = next();
      fresh[static_cast<std::size_t>(k)] = incremental[static_cast<std::size_t>(k)] + next();
    }
    for (int runs = 1; runs <= std::min(n, 3); ++runs) {
      const std::vector<int> begin = balanced_runs(fresh, incremental, runs);
      ASSERT_EQ(begin.size(), static_cast<std::size_t>(runs) + 1);
      EXPECT_EQ(begin.front(), 0);
      EXPECT_EQ(begin.back(), n);
      for (int r = 0; r < runs; ++r)
        EXPECT_LT(begin[static_cast<std::size_t>(r)], begin[static_cast<std::size_t>(r) + 1]);
      // Every cut into `runs` non-empty runs, by bit mask of run starts.
      double best = std::numeric_limits<double>::infinity();
      for (unsigned mask = 0; mask < (1u << n); ++mask) {
        if (!(mask & 1u) || __builtin_popcount(mask) != runs) continue;
        std::vector<int> cut;
        for (int k = 0; k < n; ++k)
          if (mask & (1u << k)) cut.push_back(k);
        cut.push_back(n);
        best = std::min(best, largest_run_cost(fresh, incremental, cut));
      }
      EXPECT_EQ(largest_run_cost(fresh, incremental, begin), best) << "n " << n << " runs " << runs;
    }
  }
}

TEST(AdaptiveSweep, RejectsEntropyOffAndBadSweepOptions) {
  const cv::Mat a = load_sample_gray("boat", "img1.png");
  EXPECT_THROW(adapt(view_of(a), view_of(a), options_for_mode(Mode::orbslam2)), Error);
  SweepOptions bad;
  bad.step = 0;
  EXPECT_THROW(adapt(view_of(a), view_of(a), {}, bad), Error);
  bad = {};
  bad.min_inliers = 2;
  EXPECT_THROW(adapt(view_of(a), view_of(a), {}, bad), Error);
}

}  // namespace
}  // namespace aief

// Option validation at the API boundary: every invalid value gets an aief::Error naming it.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "aief/options.hpp"

namespace aief {
namespace {

template <class Mutate>
std::string error_of(Mutate mutate) {
  ExtractorOptions options;
  mutate(options);
  try {
    Extractor extractor(options);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(Options, DefaultsAreValidAndFollowOrbSlam2) {
  ExtractorOptions options;
  EXPECT_NO_THROW(options.validate());
  EXPECT_EQ(options.n_features, 1000);
  EXPECT_DOUBLE_EQ(options.scale_factor, 1.2);
  EXPECT_EQ(options.n_levels, 8);
  EXPECT_EQ(options.fast_threshold, 20);
  EXPECT_EQ(options.fast_min_threshold, 7);
}

TEST(Options, EveryInvalidValueIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    const char* field;
    void (*mutate)(ExtractorOptions&);
  };
  const Case cases[] = {
      {"n_features", [](ExtractorOptions& o) { o.n_features = 0; }},
      {"n_features", [](ExtractorOptions& o) { o.n_features = -5; }},
      {"scale_factor", [](ExtractorOptions& o) { o.scale_factor = 1.0; }},
      {"scale_factor", [](ExtractorOptions& o) { o.scale_factor = 0.8; }},
      {"scale_factor", [](ExtractorOptions& o) { o.scale_factor = -1.2; }},
      {"scale_factor",
       [](ExtractorOptions& o) { o.scale_factor = std::numeric_limits<double>::quiet_NaN(); }},
      {"n_levels", [](ExtractorOptions& o) { o.n_levels = 0; }},
      {"n_levels", [](ExtractorOptions& o) { o.n_levels = 1000; }},
      {"fast_threshold", [](ExtractorOptions& o) { o.fast_threshold = 0; }},
      {"fast_threshold", [](ExtractorOptions& o) { o.fast_threshold = 300; }},
      {"fast_min_threshold", [](ExtractorOptions& o) { o.fast_min_threshold = 0; }},
      {"fast_min_threshold", [](ExtractorOptions& o) { o.fast_min_threshold = 30; }},
      {"block_size", [](ExtractorOptions& o) { o.block_size = 0; }},
      {"block_size", [](ExtractorOptions& o) { o.block_size = -32; }},
      {"entropy_threshold", [](ExtractorOptions& o) { o.entropy_threshold = -1; }},
      {"entropy_threshold",
       [](ExtractorOptions& o) { o.entropy_threshold = std::numeric_limits<double>::infinity(); }},
      {"entropy_threshold",
       [](ExtractorOptions& o) { o.entropy_threshold = std::numeric_limits<double>::quiet_NaN(); }},
      {"threads", [](ExtractorOptions& o) { o.threads = -1; }},
      {"distribution", [](ExtractorOptions& o) { o.distribution = static_cast<Distribution>(9); }},
      {"entropy", [](ExtractorOptions& o) { o.entropy = static_cast<EntropyMeasure>(9); }},
      {"kernels", [](ExtractorOptions& o) { o.kernels = static_cast<KernelSet>(42); }},
      {"max_image_pixels", [](ExtractorOptions& o) { o.max_image_pixels = 0; }},
      {"max_image_pixels",
       [](ExtractorOptions& o) { o.max_image_pixels = kLargestMaxImagePixels + 1; }},
      {"candidate_pool", [](ExtractorOptions& o) { o.candidate_pool = 0.5; }},
      {"candidate_pool",
       [](ExtractorOptions& o) { o.candidate_pool = std::numeric_limits<double>::quiet_NaN(); }},
      {"coordinates", [](ExtractorOptions& o) { o.coordinates = static_cast<CoordinateMap>(7); }},
      {"starvation_guard",
       [](ExtractorOptions& o) { o.starvation_guard = static_cast<StarvationGuard>(7); }},
      {"candidate_ranking",
       [](ExtractorOptions& o) { o.candidate_ranking = static_cast<CandidateRanking>(5); }},
  };
  (void)nan;
  (void)inf;
  for (const Case& c : cases) {
    const std::string message = error_of(c.mutate);
    EXPECT_NE(message.find(c.field), std::string::npos)
        << "expected an error naming " << c.field << ", got '" << message << "'";
  }
}

TEST(Options, ScaleFactorIsCheckedAsTheFloatThePyramidUses) {
  // 1.00000001 is > 1 as a double but 1.0 as a float: before, it passed and every level budget
  // became 0/0 ("per octave 0 0 0 0 0 0 0 1000").
  const std::string message = error_of([](ExtractorOptions& o) { o.scale_factor = 1.00000001; });
  EXPECT_NE(message.find("scale_factor"), std::string::npos) << message;
  EXPECT_NE(message.find("1 as a float"), std::string::npos) << message;
  // The smallest scale above 1 in float is accepted, and so is 4.
  EXPECT_EQ(error_of([](ExtractorOptions& o) {
              o.scale_factor = static_cast<double>(std::nextafter(1.0f, 2.0f));
            }),
            "");
  EXPECT_EQ(error_of([](ExtractorOptions& o) { o.scale_factor = 4.0; }), "");
  EXPECT_NE(error_of([](ExtractorOptions& o) { o.scale_factor = 4.001; }).find("scale_factor"),
            std::string::npos);
}

TEST(Options, NamesRoundTrip) {
  for (Mode mode : {Mode::aief, Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy})
    EXPECT_EQ(parse_mode(to_string(mode)), mode);
  for (CoordinateMap c : {CoordinateMap::scaled, CoordinateMap::pixel_centre})
    EXPECT_EQ(parse_coordinate_map(to_string(c)), c);
  for (StarvationGuard g : {StarvationGuard::frame, StarvationGuard::level})
    EXPECT_EQ(parse_starvation_guard(to_string(g)), g);
  EXPECT_EQ(parse_candidate_pool("inf"), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_candidate_pool("1.25"), 1.25);
  EXPECT_THROW(parse_candidate_pool("0.9"), Error);
  EXPECT_THROW(parse_candidate_pool("1.5x"), Error);
  for (Distribution d : {Distribution::proportional, Distribution::quadtree})
    EXPECT_EQ(parse_distribution(to_string(d)), d);
  for (EntropyMeasure e :
       {EntropyMeasure::off, EntropyMeasure::histogram, EntropyMeasure::intensity})
    EXPECT_EQ(parse_entropy_measure(to_string(e)), e);
  for (KernelSet k : {KernelSet::auto_select, KernelSet::scalar, KernelSet::sse4_2, KernelSet::avx2,
                      KernelSet::avx512bw, KernelSet::neon64})
    EXPECT_EQ(parse_kernel_set(to_string(k)), k);
  EXPECT_THROW(parse_mode("orb"), Error);
  EXPECT_THROW(parse_kernel_set("neon"), Error);
}

TEST(Options, ModesSetDistributionAndEntropy) {
  EXPECT_EQ(options_for_mode(Mode::orbslam2).entropy, EntropyMeasure::off);
  EXPECT_EQ(options_for_mode(Mode::orbslam2).distribution, Distribution::quadtree);
  EXPECT_EQ(options_for_mode(Mode::quadtree_entropy).entropy, EntropyMeasure::histogram);
  EXPECT_EQ(options_for_mode(Mode::quadtree_entropy).distribution, Distribution::quadtree);
  EXPECT_EQ(options_for_mode(Mode::aief).distribution, Distribution::proportional);
  ExtractorOptions intensity;
  intensity.entropy = EntropyMeasure::intensity;
  EXPECT_EQ(options_for_mode(Mode::aief, intensity).entropy, EntropyMeasure::intensity);
}

TEST(Options, OnlyTheAiefModeTakesTheMatchingQualityDefaults) {
  const ExtractorOptions defaults;
  const ExtractorOptions aief = options_for_mode(Mode::aief);
  EXPECT_EQ(aief.coordinates, defaults.coordinates);
  EXPECT_EQ(aief.subpixel, defaults.subpixel);
  EXPECT_EQ(aief.candidate_pool, defaults.candidate_pool);
  EXPECT_EQ(aief.starvation_guard, defaults.starvation_guard);
  EXPECT_EQ(aief.candidate_ranking, defaults.candidate_ranking);
  EXPECT_EQ(aief.auto_requires_two_classes, defaults.auto_requires_two_classes);
  EXPECT_TRUE(defaults.auto_requires_two_classes);
  EXPECT_EQ(defaults.coordinates, CoordinateMap::pixel_centre);
  for (Mode mode : {Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy}) {
    const ExtractorOptions o = options_for_mode(mode);
    SCOPED_TRACE(to_string(mode));
    EXPECT_EQ(o.coordinates, CoordinateMap::scaled);
    EXPECT_FALSE(o.subpixel);
    EXPECT_TRUE(std::isinf(o.candidate_pool));
    EXPECT_EQ(o.starvation_guard, StarvationGuard::frame);
    EXPECT_FALSE(o.auto_skips_uniform_blocks);
    EXPECT_EQ(o.candidate_ranking, CandidateRanking::peak_score);
    EXPECT_FALSE(o.auto_requires_two_classes);
  }
  EXPECT_EQ(options_for_mode(Mode::aief_paper).distribution, Distribution::proportional);
}

}  // namespace
}  // namespace aief

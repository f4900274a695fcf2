// The whole pipeline across the option space, bit for bit: seeded random options (sizes 39..539,
// scale 1.01..4, blocks 8..1024, levels 1..14, every mode, both entropy measures, fixed and
// automatic F, the faithful mode's choices and the entropy-guided variants in any mode) on textured
// random images and crops of the real samples; under every kernel set this CPU runs at 1, 2 and 5
// threads, the same bytes as the scalar reference at 1 thread (docs/design.md §12). Each case is
// its own test, named by its index, and prints its options when it fails, so a failure reproduces
// alone: --gtest_filter='*/17'.
//
// Cost: about 12 extractions of an image of at most 539 x 539 per case; the case count is kept
// small enough for the sanitizer jobs (scripts/ci_sanitizers), which run it too.
#include <cmath>
#include <cstring>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <opencv2/core.hpp>

#include "aief/extractor.hpp"
#include "core/options/detection_smoothing_values.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

constexpr int kCases = 40;
constexpr std::uint32_t kSeed = 20260801;

struct Case {
  ExtractorOptions options;
  Mode mode = Mode::aief;
  cv::Mat image;
  std::string description;
};

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
int uniform_int(std::mt19937& rng, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

const cv::Mat& sample_image(int index) {
  static const cv::Mat samples[] = {test::load_sample_gray("graf", "img1.png"),
                                    test::load_sample_gray("boat", "img1.png"),
                                    test::load_sample_gray("leuven", "img1.png")};
  return samples[index];
}

// Case `index` of the seeded sequence: every case depends only on the seed and its index.
constexpr Mode kEveryMode[] = {Mode::aief,     Mode::aief_paper,
                               Mode::orbslam2, Mode::quadtree_entropy,
                               Mode::quality,  Mode::faithful};

Case make_case(int index) {
  std::mt19937 rng(kSeed + static_cast<std::uint32_t>(index) * 7919u);
  Case c;
  c.mode = kEveryMode[uniform_int(rng, 0, static_cast<int>(std::size(kEveryMode)) - 1)];
  ExtractorOptions base;
  // Scale factors near 1 (and some far from it), where the pyramid has many small ratios.
  base.scale_factor =
      uniform_int(rng, 0, 2) == 0 ? uniform(rng, 1.01, 1.1) : uniform(rng, 1.01, 4.0);
  base.n_levels = uniform_int(rng, 1, 14);
  // Block sides spread on a log scale over [8, 1024]: most small, some larger than the image.
  base.block_size = static_cast<int>(std::lround(std::exp2(uniform(rng, 3.0, 10.0))));
  base.n_features =
      uniform_int(rng, 1, 3) == 1 ? uniform_int(rng, 1, 100) : uniform_int(rng, 100, 3000);
  base.fast_threshold = uniform_int(rng, 5, 40);
  base.fast_min_threshold = uniform_int(rng, 1, base.fast_threshold);
  base.entropy =
      uniform_int(rng, 0, 1) == 0 ? EntropyMeasure::histogram : EntropyMeasure::intensity;
  base.entropy_threshold = uniform(rng, 0.0, 8.0);
  base.auto_threshold = uniform_int(rng, 0, 2) == 0;
  c.options = options_for_mode(c.mode, base);
  if (c.mode != Mode::orbslam2 && c.mode != Mode::faithful) c.options.entropy = base.entropy;

  // The faithful mode's four choices also in the other modes, a quarter of the cases each (their
  // own draws, so the other options of a case stay as they were).
  std::mt19937 faithful_rng(kSeed ^ (static_cast<std::uint32_t>(index) * 104729u));
  if (uniform_int(faithful_rng, 0, 3) == 0)
    c.options.pyramid_resampling = PyramidResampling::opencv;
  if (uniform_int(faithful_rng, 0, 3) == 0) c.options.detection_cells = DetectionCells::orbslam;
  if (uniform_int(faithful_rng, 0, 3) == 0) c.options.quadtree_ties = QuadtreeTies::orbslam;
  if (uniform_int(faithful_rng, 0, 3) == 0) c.options.orientation = Orientation::opencv_fast;
  // The entropy-guided variants, a quarter of the cases each, their own draws likewise.
  std::mt19937 variant_rng(kSeed ^ (static_cast<std::uint32_t>(index) * 15485863u));
  // Each where it acts (validate() refuses it elsewhere: core/options/acts_with.hpp).
  if (uniform_int(variant_rng, 0, 3) == 0 && c.options.distribution == Distribution::quadtree)
    c.options.quadtree_weight = QuadtreeWeight::entropy;
  if (uniform_int(variant_rng, 0, 3) == 0 && c.options.detection_cells == DetectionCells::blocks)
    c.options.fast_threshold_from = FastThresholdFrom::entropy;
  // The sharpened low-entropy blocks, a quarter of the cases, their own draws (the earlier cases'
  // options stay as they were).
  std::mt19937 sharpen_rng(kSeed ^ (static_cast<std::uint32_t>(index) * 32452843u));
  if (uniform_int(sharpen_rng, 0, 3) == 0) c.options.low_entropy_sharpen = true;
  // The box descriptor, a third of the cases, its own draws likewise.
  std::mt19937 descriptor_rng(kSeed ^ (static_cast<std::uint32_t>(index) * 49979687u));
  if (uniform_int(descriptor_rng, 0, 2) == 0) c.options.descriptor = DescriptorKind::box;
  // Detection on a smoothed level, a third of the cases at 1 to 4 passes, its own draws likewise.
  std::mt19937 smoothing_rng(kSeed ^ (static_cast<std::uint32_t>(index) * 67867967u));
  if (uniform_int(smoothing_rng, 0, 2) == 0)
    c.options.detection_smoothing = detection_smoothing_of_passes(uniform_int(smoothing_rng, 1, 4));
  // Scale selection, a quarter of the cases where it acts (the engine's blocks), its own draws.
  std::mt19937 scale_rng(kSeed ^ (static_cast<std::uint32_t>(index) * 86028121u));
  if (uniform_int(scale_rng, 0, 3) == 0 && c.options.detection_cells == DetectionCells::blocks)
    c.options.scale_selection = ScaleSelection::extrema;

  const int width = uniform_int(rng, 39, 539), height = uniform_int(rng, 39, 539);
  const int source = uniform_int(rng, 0, 3);
  if (source == 0) {
    c.image = test::random_textured_image(width, height, rng());
  } else {
    const cv::Mat& sample = sample_image(source - 1);
    const int w = std::min(width, sample.cols), h = std::min(height, sample.rows);
    const int x = uniform_int(rng, 0, sample.cols - w), y = uniform_int(rng, 0, sample.rows - h);
    c.image = sample(cv::Rect(x, y, w, h)).clone();
  }

  std::ostringstream out;
  out << "case " << index << ": " << c.image.cols << "x" << c.image.rows
      << (source == 0 ? " random" : " sample crop") << ", mode " << to_string(c.mode)
      << ", entropy " << to_string(c.options.entropy) << ", F "
      << (c.options.auto_threshold ? std::string("auto")
                                   : std::to_string(c.options.entropy_threshold))
      << ", scale " << c.options.scale_factor << ", levels " << c.options.n_levels << ", block "
      << c.options.block_size << ", features " << c.options.n_features << ", FAST "
      << c.options.fast_threshold << "/" << c.options.fast_min_threshold << ", pyramid "
      << to_string(c.options.pyramid_resampling) << ", cells "
      << to_string(c.options.detection_cells) << ", ties " << to_string(c.options.quadtree_ties)
      << ", orientation " << to_string(c.options.orientation) << ", quadtree weight "
      << to_string(c.options.quadtree_weight) << ", FAST threshold from "
      << to_string(c.options.fast_threshold_from) << ", low-entropy sharpen "
      << (c.options.low_entropy_sharpen ? "on" : "off") << ", descriptor "
      << to_string(c.options.descriptor) << ", detection smoothing "
      << c.options.detection_smoothing << ", scale selection "
      << to_string(c.options.scale_selection);
  c.description = out.str();
  return c;
}

// "" when both results hold the same bytes, else the first difference.
std::string first_difference(const Features& reference, const Features& other) {
  if (reference.keypoints.size() != other.keypoints.size())
    return std::to_string(reference.keypoints.size()) + " keypoints with scalar at 1 thread, " +
           std::to_string(other.keypoints.size());
  for (std::size_t i = 0; i < reference.keypoints.size(); ++i) {
    const Keypoint &r = reference.keypoints[i], &o = other.keypoints[i];
    if (std::memcmp(&r, &o, sizeof r) != 0 || reference.descriptors[i] != other.descriptors[i]) {
      std::ostringstream out;
      out << "keypoint " << i << ": reference (" << r.x << ", " << r.y << ", octave " << r.octave
          << ", angle " << r.angle_deg << ", response " << r.response << "), other (" << o.x << ", "
          << o.y << ", octave " << o.octave << ", angle " << o.angle_deg << ", response "
          << o.response << ")"
          << (reference.descriptors[i] != other.descriptors[i] ? ", descriptors differ" : "");
      return out.str();
    }
  }
  const ExtractionInfo &r = reference.info, &o = other.info;
  if (std::memcmp(&r.entropy_threshold_used, &o.entropy_threshold_used, sizeof(double)) != 0 ||
      std::memcmp(&r.image_entropy_bits, &o.image_entropy_bits, sizeof(double)) != 0 ||
      std::memcmp(&r.entropy_threshold_requested, &o.entropy_threshold_requested, sizeof(double)) !=
          0 ||
      std::memcmp(&r.auto_threshold_effectiveness, &o.auto_threshold_effectiveness,
                  sizeof(double)) != 0 ||
      r.threshold_lowered != o.threshold_lowered || r.blocks_total != o.blocks_total ||
      r.blocks_kept != o.blocks_kept)
    return "extraction info differs (threshold used " + std::to_string(r.entropy_threshold_used) +
           " vs " + std::to_string(o.entropy_threshold_used) + ", blocks kept " +
           std::to_string(r.blocks_kept) + " vs " + std::to_string(o.blocks_kept) + ")";
  return "";
}

class PipelineDifferential : public testing::TestWithParam<int> {};

// `base` under every kernel set at 1, 2 and 5 threads, except the scalar reference at 1 (TBB's
// cap on workers lifted, so 5 threads are 5 even on a 2-core machine).
template <typename Check>
void for_each_kernel_set_and_thread_count(const ExtractorOptions& base, Check check) {
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 5);
  for (KernelSet set : available_kernel_sets()) {
    for (int threads : {1, 2, 5}) {
      if (set == KernelSet::scalar && threads == 1) continue;
      ExtractorOptions options = base;
      options.kernels = set;
      options.threads = threads;
      check(options);
    }
  }
}

TEST_P(PipelineDifferential, EveryKernelSetAndThreadCountGivesTheScalarBytes) {
  const Case c = make_case(GetParam());
  SCOPED_TRACE(c.description);
  const ImageView view = view_of(c.image);
  ExtractorOptions reference_options = c.options;
  reference_options.kernels = KernelSet::scalar;
  reference_options.threads = 1;
  const Features reference = Extractor(reference_options).extract(view);
  for_each_kernel_set_and_thread_count(c.options, [&](const ExtractorOptions& options) {
    Extractor extractor(options);
    EXPECT_EQ(first_difference(reference, extractor.extract(view)), "")
        << to_string(options.kernels) << " at " << options.threads << " thread(s)";
  });
}

// Given keypoints (Extractor::describe): the case's own keypoints, which must come back with their
// bytes, and as many again at seeded random positions and octaves (some near or past the edges,
// which the border rule removes), the same under every kernel set as under the scalar reference.
TEST_P(PipelineDifferential, DescribingGivenKeypointsGivesTheScalarBytesAndTheExtractedOnes) {
  const Case c = make_case(GetParam());
  SCOPED_TRACE(c.description);
  const ImageView view = view_of(c.image);
  ExtractorOptions reference_options = c.options;
  reference_options.kernels = KernelSet::scalar;
  Extractor reference_extractor(reference_options);
  Features extracted = reference_extractor.extract(view);
  extracted.info = ExtractionInfo{};  // describe() reports no extraction
  EXPECT_EQ(first_difference(extracted, reference_extractor.describe(view, extracted.keypoints)),
            "")
      << "describing the extracted keypoints";

  std::vector<Keypoint> given = extracted.keypoints;
  std::mt19937 rng(kSeed ^ static_cast<std::uint32_t>(GetParam()));
  for (std::size_t i = 0; i < extracted.keypoints.size() + 50; ++i) {
    Keypoint kp;
    kp.x = static_cast<float>(uniform(rng, -5.0, c.image.cols + 5.0));
    kp.y = static_cast<float>(uniform(rng, -5.0, c.image.rows + 5.0));
    kp.octave = uniform_int(rng, 0, c.options.n_levels - 1);
    kp.angle_deg = static_cast<float>(uniform(rng, 0.0, 359.9));
    given.push_back(kp);
  }
  for (GivenAngles angles : {GivenAngles::recompute, GivenAngles::keep}) {
    SCOPED_TRACE(angles == GivenAngles::keep ? "given angles kept" : "angles recomputed");
    std::vector<std::int32_t> reference_kept;
    Features reference;
    reference_extractor.describe(view, given, reference, &reference_kept, angles);
    for (KernelSet set : available_kernel_sets()) {
      if (set == KernelSet::scalar) continue;
      ExtractorOptions options = c.options;
      options.kernels = set;
      std::vector<std::int32_t> kept;
      Features described;
      Extractor(options).describe(view, given, described, &kept, angles);
      EXPECT_EQ(first_difference(reference, described), "") << to_string(set);
      EXPECT_EQ(kept, reference_kept) << to_string(set);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(SeededCases, PipelineDifferential, testing::Range(0, kCases));

// The carried F through a video (docs/design.md §10): the sweep spread over frames by its
// estimates of work (core/sweep/spread_sweep.hpp) must switch F at the same frame and give the same
// bytes on every frame under every kernel set and thread count. A case takes a seeded case's
// options in a mode with an entropy mask, carried F, a sweep due every 1-4 frames, and a video
// panning over a crop of it, long enough for sweeps to complete.
constexpr int kCarriedCases = 6;
constexpr int kCarriedFrames = 60;

struct CarriedCase {
  ExtractorOptions options;
  std::vector<cv::Mat> frames;
  std::string description;
};

CarriedCase make_carried_case(int index) {
  const Case base = make_case(index);
  std::mt19937 rng(kSeed ^ (static_cast<std::uint32_t>(index) * 2654435761u));
  CarriedCase c;
  ExtractorOptions asked;
  asked.n_features = uniform_int(rng, 50, 400);
  asked.n_levels = uniform_int(rng, 1, 6);
  asked.scale_factor = base.options.scale_factor < 1.1 ? 1.2 : base.options.scale_factor;
  asked.block_size = std::min(base.options.block_size, 64);
  const Mode modes[] = {Mode::aief, Mode::aief_paper, Mode::quadtree_entropy};
  c.options = options_for_mode(modes[index % 3], asked);
  c.options.entropy =
      uniform_int(rng, 0, 1) == 0 ? EntropyMeasure::histogram : EntropyMeasure::intensity;
  c.options.auto_threshold = false;
  c.options.carried_threshold = true;
  c.options.carry_every = uniform_int(rng, 1, 4);
  const cv::Mat& sample = sample_image(index % 3);
  const int width = uniform_int(rng, 120, 240), height = uniform_int(rng, 90, 180);
  const int dx = uniform_int(rng, -3, 3), dy = uniform_int(rng, -2, 2);
  const int x0 = sample.cols / 2 - width / 2, y0 = sample.rows / 2 - height / 2;
  for (int t = 0; t < kCarriedFrames; ++t)
    c.frames.push_back(sample(cv::Rect(x0 + dx * t, y0 + dy * t, width, height)).clone());
  std::ostringstream out;
  out << "carried case " << index << ": " << width << "x" << height << " panning " << dx << ","
      << dy << ", mode " << to_string(modes[index % 3]) << ", entropy "
      << to_string(c.options.entropy) << ", features " << c.options.n_features << ", levels "
      << c.options.n_levels << ", scale " << c.options.scale_factor << ", block "
      << c.options.block_size << ", carry every " << c.options.carry_every;
  c.description = out.str();
  return c;
}

std::vector<Features> run_frames(const CarriedCase& c, const ExtractorOptions& options) {
  Extractor extractor(options);
  std::vector<Features> out(c.frames.size());
  for (std::size_t t = 0; t < c.frames.size(); ++t) extractor.extract(view_of(c.frames[t]), out[t]);
  return out;
}

class CarriedVideoDifferential : public testing::TestWithParam<int> {};

TEST_P(CarriedVideoDifferential, EveryKernelSetAndThreadCountGivesTheScalarBytesOnEveryFrame) {
  const CarriedCase c = make_carried_case(GetParam());
  SCOPED_TRACE(c.description);
  ExtractorOptions reference_options = c.options;
  reference_options.kernels = KernelSet::scalar;
  reference_options.threads = 1;
  const std::vector<Features> reference = run_frames(c, reference_options);
  for_each_kernel_set_and_thread_count(c.options, [&](const ExtractorOptions& options) {
    const std::vector<Features> other = run_frames(c, options);
    for (std::size_t t = 0; t < reference.size(); ++t)
      ASSERT_EQ(first_difference(reference[t], other[t]), "")
          << to_string(options.kernels) << " at " << options.threads << " thread(s), frame " << t;
  });
}

INSTANTIATE_TEST_SUITE_P(SeededCases, CarriedVideoDifferential, testing::Range(0, kCarriedCases));

// The carried cases do what they are for: in most, a sweep completes and changes F mid-video.
TEST(PipelineDifferentialCases, CarriedCasesChangeFMidVideo) {
  int changed = 0;
  for (int i = 0; i < kCarriedCases; ++i) {
    const CarriedCase c = make_carried_case(i);
    ExtractorOptions options = c.options;
    options.kernels = KernelSet::scalar;
    const std::vector<Features> frames = run_frames(c, options);
    changed += frames.front().info.entropy_threshold_requested !=
               frames.back().info.entropy_threshold_requested;
  }
  EXPECT_GE(changed, kCarriedCases / 2);
}

// The generator reaches the corners of the option space it claims to cover.
TEST(PipelineDifferentialCases, CoverEveryModeMeasureAndBothKindsOfThreshold) {
  std::map<Mode, int> modes;
  int measures[3] = {}, automatic = 0, fixed = 0, small_blocks = 0, large_blocks = 0, one_level = 0,
      many_levels = 0, near_one = 0, large_scale = 0;
  for (int i = 0; i < kCases; ++i) {
    const Case c = make_case(i);
    const ExtractorOptions& o = c.options;
    ++modes[c.mode];
    ++measures[static_cast<int>(o.entropy)];
    (o.auto_threshold ? automatic : fixed) += 1;
    small_blocks += o.block_size <= 16;
    large_blocks += o.block_size >= 256;
    one_level += o.n_levels <= 2;
    many_levels += o.n_levels >= 12;
    near_one += o.scale_factor < 1.1;
    large_scale += o.scale_factor > 2.5;
  }
  for (Mode mode : kEveryMode) EXPECT_GT(modes[mode], 0) << to_string(mode);
  EXPECT_GT(measures[static_cast<int>(EntropyMeasure::histogram)], 0);
  EXPECT_GT(measures[static_cast<int>(EntropyMeasure::intensity)], 0);
  for (int count : {automatic, fixed, small_blocks, large_blocks, one_level, many_levels, near_one,
                    large_scale})
    EXPECT_GT(count, 0);
}

}  // namespace
}  // namespace aief

// aief bench IMAGE [--pair IMAGE2] [--repeat N] [--threads T] [--kernels K]: one JSON line with
// the median milliseconds of each stage and of the whole extract, and of cv::ORB on the same gray
// image; with --pair, also of the adaptive sweep on the pair and of what it replaces (extract
// both + one match), so the sweep's cost ratio is one command.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "aief/adapt.hpp"
#include "aief/extractor.hpp"
#include "aief/match.hpp"
#include "core/frame/frame_pipeline.hpp"
#include "core/frame/stage_times.hpp"
#include "io/json_writer.hpp"
#include "simd/kernels.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/read_image.hpp"

namespace aief::cli {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// bench's own flags, each with its --help text.
const std::vector<FlagSpec> kOwnFlags = {
    {"--repeat", "", true, "N", "runs per measurement (default 21)"},
    {"--pair", "", true, "IMAGE2", "also time the adaptive sweep on the pair"}};

void print_help() {
  std::cout
      << "usage: aief bench IMAGE [--pair IMAGE2] [--repeat N] [--threads T] [--kernels K] "
         "[options]\n\n"
      << "Prints one JSON line: median milliseconds over N runs of the whole extract and of\n"
      << "each of its stages, timed inside the same pipeline (pyramid_ms, entropy_ms, "
         "fast_ms,\n"
      << "select_ms: distribution + description, frame_ms: automatic F, fallback, output; "
         "each\n"
      << "summed over levels and threads), and of cv::ORB(1000, 1.2, 8).detectAndCompute on\n"
      << "the same gray image, with their ratio.\n"
      << "cv::ORB runs on one OpenCV thread, as in bench/RESULTS.md.\n"
      << "With --pair: sweep_ms (the adaptive sweep on IMAGE, IMAGE2), pair_ms (extract both\n"
      << "and one match) and sweep_ratio = sweep_ms / pair_ms.\n\n"
      << help_of(kOwnFlags) << extractor_flags_help();
}

// The whole extract, as a user calls it: milliseconds of each run (`features`: the last
// frame's).
std::vector<double> time_extract(Extractor& extractor, const GrayImage& image, int repeat,
                                 Features& features) {
  extractor.extract(image.view(), features);  // warm: buffers sized
  std::vector<double> total;
  for (int i = 0; i < repeat; ++i) {
    const auto start = Clock::now();
    extractor.extract(image.view(), features);
    total.push_back(ms_since(start));
  }
  return total;
}

// Stages: the same pipeline extract() runs (core/frame/frame_pipeline.hpp), with a stage clock, in
// runs of their own so the totals of time_extract read no clock. A stage's milliseconds are
// summed over the levels, and so over the threads that ran them side by side. The median of each
// stage, by Stage.
std::vector<double> stage_medians(const ExtractorOptions& options, const GrayImage& image,
                                  int repeat) {
  FramePipeline pipeline(options, kernel_table(options.kernels), options.threads);
  StageTimes times;
  std::vector<std::vector<double>> stage_ms(kStageCount);
  Features staged;
  pipeline.extract(image.view(), staged);  // warm: buffers sized
  for (int i = 0; i < repeat; ++i) {
    times.clear();
    pipeline.extract(image.view(), staged, &times);
    for (std::size_t k = 0; k < kStageCount; ++k)
      stage_ms[k].push_back(times.total_ms(static_cast<Stage>(k)));
  }
  std::vector<double> medians;
  for (const std::vector<double>& runs : stage_ms) medians.push_back(median(runs));
  return medians;
}

struct OpenCvOrbTimes {
  std::vector<double> ms;
  int keypoints = 0;
};

// cv::ORB on the same gray image, same process, on one OpenCV thread like bench/RESULTS.md
// (OpenCV's own worker threads would otherwise share the cores with the timing).
OpenCvOrbTimes time_opencv_orb(const GrayImage& image, int repeat) {
  const int opencv_threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const cv::Mat gray(image.height(), image.width(), CV_8UC1,
                     const_cast<std::uint8_t*>(image.data()));
  cv::Ptr<cv::ORB> orb = cv::ORB::create(1000, 1.2f, 8);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  OpenCvOrbTimes times;
  for (int i = 0; i < repeat; ++i) {
    const auto start = Clock::now();
    orb->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
    times.ms.push_back(ms_since(start));
  }
  cv::setNumThreads(opencv_threads);
  times.keypoints = static_cast<int>(keypoints.size());
  return times;
}

struct SweepTimes {
  std::vector<double> sweep_ms, pair_ms;
  std::size_t pair_matches = 0;
};

// The sweep on the pair beside what it replaces: extract both images and match once, in
// alternation.
SweepTimes time_sweep_and_pair(const ExtractorOptions& options, Extractor& extractor,
                               const GrayImage& image, const GrayImage& second, int repeat) {
  SweepTimes times;
  AdaptiveSweep sweep(options);  // reused, as the extractor is
  AdaptResult result;
  sweep.run(image.view(), second.view(), result);  // warm
  Features features, other;
  for (int i = 0; i < repeat; ++i) {
    auto start = Clock::now();
    sweep.run(image.view(), second.view(), result);
    times.sweep_ms.push_back(ms_since(start));
    start = Clock::now();
    extractor.extract(image.view(), features);
    extractor.extract(second.view(), other);
    times.pair_matches = match_descriptors(features.descriptors, other.descriptors).size();
    times.pair_ms.push_back(ms_since(start));
  }
  return times;
}

// Everything bench measures on one image (and pair).
struct BenchMeasures {
  std::string kernels;
  int keypoints = 0;
  std::vector<double> aief_ms;   // the whole extract, each run
  std::vector<double> stage_ms;  // the median of each stage, by Stage
  OpenCvOrbTimes orb;
  std::optional<SweepTimes> pair;  // with --pair
};

BenchMeasures measure(const ExtractorOptions& options, const GrayImage& image,
                      const GrayImage* second, int repeat) {
  BenchMeasures measures;
  Extractor extractor(options);
  Features features;
  measures.kernels = extractor.kernel_name();
  measures.aief_ms = time_extract(extractor, image, repeat, features);
  measures.keypoints = static_cast<int>(features.keypoints.size());
  measures.stage_ms = stage_medians(options, image, repeat);
  measures.orb = time_opencv_orb(image, repeat);
  if (second) measures.pair = time_sweep_and_pair(options, extractor, image, *second, repeat);
  return measures;
}

// The one JSON line.
std::string bench_json(const std::string& path, const GrayImage& image,
                       const ExtractorOptions& options, int repeat,
                       const std::optional<std::string>& pair_path, const BenchMeasures& m) {
  const auto stage = [&](Stage s) { return m.stage_ms[static_cast<std::size_t>(s)]; };
  const double aief_ms = median(m.aief_ms), orb_ms = median(m.orb.ms);
  std::ostringstream text;
  io::JsonWriter json(text);
  json.set_newline_depth(0);
  json.begin_object();
  json.field("image", path).field("width", image.width()).field("height", image.height());
  json.field("kernels", m.kernels).field("threads", options.threads).field("repeat", repeat);
  json.field("keypoints", m.keypoints);
  json.field("pyramid_ms", stage(Stage::pyramid)).field("entropy_ms", stage(Stage::entropy));
  json.field("fast_ms", stage(Stage::detect)).field("select_ms", stage(Stage::select));
  json.field("frame_ms", stage(Stage::frame));
  json.field("aief_ms", aief_ms).field("opencv_orb_ms", orb_ms);
  json.field("opencv_orb_keypoints", m.orb.keypoints);
  json.field("speedup_vs_opencv_orb", orb_ms / aief_ms);
  if (pair_path && m.pair) {
    const double sweep_ms = median(m.pair->sweep_ms), pair_ms = median(m.pair->pair_ms);
    json.field("pair", *pair_path).field("sweep_ms", sweep_ms).field("pair_ms", pair_ms);
    json.field("sweep_ratio", sweep_ms / pair_ms)
        .field("pair_matches", static_cast<int>(m.pair->pair_matches));
  }
  json.end_object();
  return text.str();
}

}  // namespace

int run_bench(const Arguments& arguments) {
  std::vector<FlagSpec> spec = extractor_flags();
  spec.insert(spec.end(), kOwnFlags.begin(), kOwnFlags.end());
  const std::optional<Args> parsed = command_args(arguments, spec, print_help);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (args.positionals().size() != 1)
    throw UsageError("bench expects one IMAGE (aief bench --help)");
  const int repeat = args.get_int("--repeat", 21, 1, 100000);
  const ExtractorOptions options = extractor_options(args);
  const std::string& path = args.positionals()[0];
  const GrayImage image = read_image_reporting(path, options.max_image_pixels);
  const std::optional<std::string> pair_path = args.get("--pair");
  if (pair_path) require_entropy_to_sweep(args, options, "bench --pair");
  const GrayImage second =
      pair_path ? read_image_reporting(*pair_path, options.max_image_pixels) : GrayImage();
  const BenchMeasures measures = measure(options, image, pair_path ? &second : nullptr, repeat);
  std::cout << bench_json(path, image, options, repeat, pair_path, measures);
  return 0;
}

}  // namespace aief::cli

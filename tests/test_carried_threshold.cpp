// F carried through a video (core/sweep/carried_threshold.hpp): the sweep spread over the frames
// after a pair (core/sweep/spread_sweep.hpp) gives one-shot adapt()'s F on that pair from the frame
// after it completes, no frame's share above its budget, and the same bytes twice, with any thread
// count and any kernel set.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/options/option_table.hpp"
#include "core/sweep/carried_threshold.hpp"
#include "core/sweep/spread_sweep.hpp"
#include "simd/kernels.hpp"
#include "tests/features_hash.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

// A video: a 320 x 240 window panning over leuven's first image, 3 px right and 1 px down
// per frame, dimming by 1 gray level per frame (leuven's own theme: light change).
std::vector<cv::Mat> panning_frames(int count) {
  const cv::Mat scene = test::load_sample_gray("leuven", "img1.png");
  std::vector<cv::Mat> frames;
  for (int t = 0; t < count; ++t) {
    cv::Mat frame;
    scene(cv::Rect(100 + 3 * t, 80 + t, 320, 240)).convertTo(frame, CV_8U, 1.0, -1.0 * t);
    frames.push_back(frame);
  }
  return frames;
}

ExtractorOptions carried_options() {
  ExtractorOptions options;
  options.n_features = 500;
  options.carried_threshold = true;
  options.carry_every = 20;
  return options;
}

// The F each frame requested and the hash of each frame's output.
struct VideoRun {
  std::vector<double> thresholds;
  std::vector<std::uint64_t> hashes;
};

VideoRun run_video(const std::vector<cv::Mat>& frames, const ExtractorOptions& options) {
  Extractor extractor(options);
  VideoRun run;
  Features features;
  for (const cv::Mat& frame : frames) {
    extractor.extract(view_of(frame), features);
    run.thresholds.push_back(features.info.entropy_threshold_requested);
    run.hashes.push_back(test::features_hash(features));
  }
  return run;
}

// Runs CarriedThreshold over frames [begin, end), as the Extractor does after each extraction;
// returns the F each frame requested.
std::vector<double> run_carried(CarriedThreshold& carried, const std::vector<cv::Mat>& frames,
                                int begin, int end) {
  std::vector<double> f;
  for (int t = begin; t < end; ++t) {
    f.push_back(carried.threshold());
    carried.after_frame(view_of(frames[static_cast<std::size_t>(t)]));
  }
  return f;
}

TEST(CarriedThreshold, FirstSweepGivesAdaptsFOnTheFirstPairFromTheFrameAfterItCompletes) {
  const std::vector<cv::Mat> frames = panning_frames(90);
  const ExtractorOptions options = carried_options();
  ExtractorOptions one_shot = options;
  one_shot.carried_threshold = false;
  const AdaptResult expected = adapt(view_of(frames[0]), view_of(frames[1]), one_shot);
  ASSERT_TRUE(expected.found);
  ASSERT_NE(expected.threshold, ExtractorOptions{}.entropy_threshold) << "no change to see";

  CarriedThreshold carried(options, kernel_table(KernelSet::scalar));
  const double budget = SpreadSweep::frame_budget(view_of(frames[0]), options.n_features);
  for (int t = 0; t < static_cast<int>(frames.size()) && carried.sweeps_completed() == 0; ++t) {
    carried.after_frame(view_of(frames[static_cast<std::size_t>(t)]));
    // Within the frame's budget, unless its step is one piece larger than the budget alone.
    if (carried.last_step_pieces() > 1) {
      EXPECT_LE(carried.last_step_work(), budget) << "frame " << t;
    }
  }
  ASSERT_EQ(carried.sweeps_completed(), 1);
  EXPECT_EQ(carried.last_sweep().threshold, expected.threshold);
  EXPECT_EQ(carried.last_sweep().curve.size(), expected.curve.size());
  // Spread over many frames.
  const long long completed_after = carried.last_sweep_completed_after();
  EXPECT_GT(completed_after, 10);
  ASSERT_LT(completed_after + 1, static_cast<long long>(frames.size()));

  // The Extractor: the default F up to that frame, the sweep's from the next one on.
  const VideoRun run = run_video(frames, options);
  for (int t = 0; t <= completed_after + 1; ++t) {
    const double wanted =
        t <= completed_after ? ExtractorOptions{}.entropy_threshold : expected.threshold;
    EXPECT_EQ(run.thresholds[static_cast<std::size_t>(t)], wanted) << "frame " << t;
  }
}

// Runs frames from t on until `completed` sweeps have completed or the frames run out; returns
// the next frame.
int run_until_completed(CarriedThreshold& carried, const std::vector<cv::Mat>& frames, int t,
                        int completed) {
  for (; t < static_cast<int>(frames.size()) && carried.sweeps_completed() < completed; ++t)
    carried.after_frame(view_of(frames[static_cast<std::size_t>(t)]));
  return t;
}

TEST(CarriedThreshold, SweepsStartEveryNFramesNeverWhileOneRunsAndOnRequest) {
  const std::vector<cv::Mat> frames = panning_frames(150);
  ExtractorOptions options = carried_options();
  options.n_features = 250;
  options.n_levels = 4;
  options.carry_every = 12;
  ExtractorOptions one_shot = options;
  one_shot.carried_threshold = false;
  const KernelTable& kernels = kernel_table(KernelSet::scalar);
  CarriedThreshold carried(options, kernels);
  int t = run_until_completed(carried, frames, 0, 1);
  ASSERT_EQ(carried.sweeps_completed(), 1);
  const long long first_end = carried.last_sweep_completed_after();
  ASSERT_GT(first_end, 1 + options.carry_every) << "the test wants a sweep longer than carry_every";
  // The second sweep was due since frame 13: it starts with the frame after the first completed,
  // on the pair (first_end, first_end + 1), and gives adapt's answer on it.
  t = run_until_completed(carried, frames, t, 2);
  ASSERT_EQ(carried.sweeps_completed(), 2);
  const AdaptResult second =
      adapt(view_of(frames[static_cast<std::size_t>(first_end)]),
            view_of(frames[static_cast<std::size_t>(first_end + 1)]), one_shot);
  EXPECT_EQ(carried.last_sweep().threshold, second.threshold);
  EXPECT_EQ(carried.last_sweep().curve.size(), second.curve.size());
  EXPECT_EQ(carried.frames_seen(), t);

  // On request: a sweep starts with the next frame, whatever carry_every says.
  options.carry_every = 1000;
  CarriedThreshold requested(options, kernels);
  t = run_until_completed(requested, frames, 0, 1);
  ASSERT_EQ(requested.sweeps_completed(), 1);
  const int asked_at = t + 2;
  run_carried(requested, frames, t, asked_at);
  requested.request_sweep();
  run_until_completed(requested, frames, asked_at, 2);
  ASSERT_EQ(requested.sweeps_completed(), 2);
  const AdaptResult on_request =
      adapt(view_of(frames[static_cast<std::size_t>(asked_at - 1)]),
            view_of(frames[static_cast<std::size_t>(asked_at)]), one_shot);
  EXPECT_EQ(requested.last_sweep().threshold, on_request.threshold);
  EXPECT_EQ(requested.last_sweep().curve.size(), on_request.curve.size());
}

TEST(CarriedThreshold, SameBytesTwiceWithAnyThreadCountAndKernelSet) {
  // Long enough for a spread sweep to complete and the next to start: the F switches mid-video.
  const std::vector<cv::Mat> frames = panning_frames(70);
  ExtractorOptions options = carried_options();
  options.carry_every = 3;  // sweeps back to back: every frame runs a step
  options.kernels = KernelSet::scalar;
  options.threads = 1;
  const VideoRun reference = run_video(frames, options);
  ASSERT_NE(reference.thresholds.front(), reference.thresholds.back()) << "no sweep completed";
  EXPECT_EQ(run_video(frames, options).hashes, reference.hashes) << "run twice";
  options.threads = 2;
  EXPECT_EQ(run_video(frames, options).hashes, reference.hashes) << "2 threads";
  for (KernelSet set : available_kernel_sets()) {
    options.kernels = set;
    EXPECT_EQ(run_video(frames, options).hashes, reference.hashes) << "kernels " << to_string(set);
  }
}

TEST(CarriedThreshold, OtherModesIgnoreTheSweepRequest) {
  const std::vector<cv::Mat> frames = panning_frames(3);
  ExtractorOptions fixed = carried_options();
  fixed.carried_threshold = false;
  Extractor plain(fixed);
  plain.request_threshold_sweep();
  for (const cv::Mat& frame : frames)
    EXPECT_EQ(plain.extract(view_of(frame)).info.entropy_threshold_requested,
              fixed.entropy_threshold);
}

// The option through the table: the word, the frame count, and what is refused.
ExtractorOptions resolve(const std::vector<std::pair<std::string, std::string>>& given) {
  std::vector<option_table::GivenOption> options;
  for (const auto& [key, text] : given) options.push_back({&option_table::row(key), text, key});
  return option_table::resolve_options(options);
}

TEST(CarriedThreshold, OptionRowsAndRefusedValues) {
  const ExtractorOptions carried =
      resolve({{"entropy_threshold", "carried"}, {"carry_every", "25"}});
  EXPECT_TRUE(carried.carried_threshold);
  EXPECT_FALSE(carried.auto_threshold);
  EXPECT_EQ(carried.carry_every, 25);
  EXPECT_EQ(carried.entropy_threshold, ExtractorOptions{}.entropy_threshold);  // until a sweep
  EXPECT_FALSE(resolve({{"entropy_threshold", "3.5"}}).carried_threshold);
  EXPECT_FALSE(resolve({{"entropy_threshold", "auto"}}).carried_threshold);

  const auto message_of = [](const std::vector<std::pair<std::string, std::string>>& given) {
    try {
      resolve(given);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message_of({{"carry_every", "0"}}),
            "carry_every expects an integer in [1, 1000000], got '0'");
  EXPECT_EQ(message_of({{"carry_every", "ten"}}),
            "carry_every expects an integer in [1, 1000000], got 'ten'");
  EXPECT_EQ(message_of({{"entropy_threshold", "carry"}}),
            "entropy_threshold expects a number in [0, 64], auto or carried, got 'carry'");
  EXPECT_NE(message_of({{"entropy_threshold", "carried"}, {"entropy", "off"}}).find("off"),
            std::string::npos);

  ExtractorOptions both;
  both.auto_threshold = true;
  both.carried_threshold = true;
  EXPECT_THROW(both.validate(), Error);
  ExtractorOptions zero;
  zero.carry_every = 0;
  EXPECT_THROW(Extractor{zero}, Error);
}

}  // namespace
}  // namespace aief

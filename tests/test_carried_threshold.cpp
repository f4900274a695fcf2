// F carried through a video (core/carried_threshold.hpp): the sweep spread over the frames after a
// pair gives one-shot adapt()'s F on that pair, after the documented number of frames, and the
// same bytes twice, with any thread count and any kernel set.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/carried_threshold.hpp"
#include "core/option_table.hpp"
#include "simd/kernels.hpp"
#include "tests/features_hash.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

// A short video: a 320 x 240 window panning over leuven's first image, 3 px right and 2 px down
// per frame, dimming by 2 gray levels per frame (leuven's own theme: light change).
std::vector<cv::Mat> panning_frames(int count) {
  const cv::Mat scene = test::load_sample_gray("leuven", "img1.png");
  std::vector<cv::Mat> frames;
  for (int t = 0; t < count; ++t) {
    cv::Mat frame;
    scene(cv::Rect(100 + 3 * t, 80 + 2 * t, 320, 240)).convertTo(frame, CV_8U, 1.0, -2.0 * t);
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

TEST(CarriedThreshold, FirstSweepGivesAdaptsFOnTheFirstPairAfterTheDocumentedFrames) {
  const std::vector<cv::Mat> frames = panning_frames(24);
  ExtractorOptions one_shot = carried_options();
  one_shot.carried_threshold = false;
  const AdaptResult expected = adapt(view_of(frames[0]), view_of(frames[1]), one_shot);
  ASSERT_TRUE(expected.found);
  ASSERT_NE(expected.threshold, ExtractorOptions{}.entropy_threshold) << "no change to see";
  // The sweep starts with frame 1 and its F applies from frame 1 + steps_of(C) on.
  const int applies_from = 1 + CarriedThreshold::steps_of(static_cast<int>(expected.curve.size()));
  ASSERT_LE(applies_from, 1 + carried_options().carry_every) << "the second sweep must not start before the first F applies";

  const VideoRun run = run_video(frames, carried_options());
  for (int t = 0; t < static_cast<int>(frames.size()); ++t) {
    const double wanted =
        t < applies_from ? ExtractorOptions{}.entropy_threshold : expected.threshold;
    EXPECT_EQ(run.thresholds[static_cast<std::size_t>(t)], wanted) << "frame " << t;
  }
}

TEST(CarriedThreshold, SweepsStartEveryNFramesAndOnRequest) {
  const std::vector<cv::Mat> frames = panning_frames(30);
  ExtractorOptions options = carried_options();
  options.n_levels = 4;
  options.carry_every = 12;
  ExtractorOptions one_shot = options;
  one_shot.carried_threshold = false;
  const KernelTable& kernels = kernel_table(KernelSet::scalar);
  CarriedThreshold carried(options, kernels);
  std::vector<double> f;
  for (const cv::Mat& frame : frames) {
    f.push_back(carried.threshold());
    carried.after_frame(view_of(frame));
  }
  // Sweeps on the pairs (0, 1), (12, 13), (24, 25); the last one's F is adapt's on its pair.
  EXPECT_EQ(carried.sweeps_completed(), 2 + (25 + CarriedThreshold::steps_of(40) <= 30 ? 1 : 0));
  const AdaptResult second = adapt(view_of(frames[12]), view_of(frames[13]), one_shot);
  const int second_applies = 13 + CarriedThreshold::steps_of(static_cast<int>(second.curve.size()));
  if (second.found) {
    EXPECT_EQ(f[static_cast<std::size_t>(second_applies)], second.threshold);
  }
  EXPECT_EQ(carried.frames_seen(), 30);

  // On request: a sweep starts with the next frame, whatever carry_every says.
  options.carry_every = 1000;
  CarriedThreshold requested(options, kernels);
  for (int t = 0; t < 20; ++t) {
    if (t == 14) requested.request_sweep();
    requested.after_frame(view_of(frames[static_cast<std::size_t>(t)]));
  }
  EXPECT_EQ(requested.sweeps_completed(), 1);  // the first pair's; the requested one runs
  for (int t = 20; t < 30; ++t) requested.after_frame(view_of(frames[static_cast<std::size_t>(t)]));
  EXPECT_EQ(requested.sweeps_completed(), 2);
  const AdaptResult on_request = adapt(view_of(frames[13]), view_of(frames[14]), one_shot);
  EXPECT_EQ(requested.last_sweep().threshold, on_request.threshold);
  EXPECT_EQ(requested.last_sweep().curve.size(), on_request.curve.size());
}

TEST(CarriedThreshold, SameBytesTwiceWithAnyThreadCountAndKernelSet) {
  const std::vector<cv::Mat> frames = panning_frames(12);
  ExtractorOptions options = carried_options();
  options.carry_every = 3;  // sweeps back to back: every frame runs a step
  options.kernels = KernelSet::scalar;
  options.threads = 1;
  const VideoRun reference = run_video(frames, options);
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

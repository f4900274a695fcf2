// The detection mask (Extractor::extract with a mask, core/level/caller_mask.hpp): applied before
// the candidate pool and the distribution, so the budget is filled inside it; bit-exact across
// kernel sets and threads; an all-allowing mask is no mask.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

constexpr Mode kEveryMode[] = {Mode::aief, Mode::aief_paper, Mode::orbslam2,
                               Mode::quadtree_entropy};

using test::same_bytes;

bool allowed_at(const cv::Mat& mask, const Keypoint& kp) {
  const int x = std::clamp(static_cast<int>(std::lround(kp.x)), 0, mask.cols - 1);
  const int y = std::clamp(static_cast<int>(std::lround(kp.y)), 0, mask.rows - 1);
  return mask.at<std::uint8_t>(y, x) != 0;
}

Features extract_masked(const cv::Mat& image, const cv::Mat& mask,
                        const ExtractorOptions& options) {
  Features out;
  Extractor(options).extract(view_of(image), view_of(mask), out);
  return out;
}

// The figure that showed the problem: with a mask keeping the left half, dropping the masked
// keypoints after extraction (the rule before the mask reached the engine) kept 549 of 1000 on
// graf in the default mode (460-562 over the images and modes); cv::ORB returns its whole budget
// inside the mask, and so does aief now, in every mode.
TEST(DetectionMask, TheBudgetIsFilledInsideTheMask) {
  for (const char* sequence : {"graf", "boat", "leuven"}) {
    const cv::Mat image = test::load_sample_gray(sequence, "img1.png");
    cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
    mask(cv::Rect(0, 0, image.cols / 2, image.rows)).setTo(255);  // keypoints in the left half only
    for (Mode mode : kEveryMode) {
      const ExtractorOptions options = options_for_mode(mode);
      const Features unmasked = extract(view_of(image), options);
      int after_the_fact = 0;
      for (const Keypoint& kp : unmasked.keypoints) after_the_fact += allowed_at(mask, kp);
      const Features masked = extract_masked(image, mask, options);
      std::printf(
          "%s, %s, mask keeping the left half: %d of %d kept when masked after extraction, %zu "
          "with the mask in detection\n",
          sequence, std::string(to_string(mode)).c_str(), after_the_fact, options.n_features,
          masked.keypoints.size());
      EXPECT_EQ(static_cast<int>(masked.keypoints.size()), options.n_features)
          << sequence << " " << to_string(mode);
      EXPECT_LT(after_the_fact, options.n_features * 3 / 4) << sequence << " " << to_string(mode);
      for (const Keypoint& kp : masked.keypoints)
        ASSERT_TRUE(allowed_at(mask, kp))
            << sequence << " " << to_string(mode) << ": keypoint at (" << kp.x << ", " << kp.y
            << ") octave " << kp.octave << " outside the mask";
    }
  }
}

TEST(DetectionMask, AMaskAllowingEveryPixelIsNoMask) {
  const cv::Mat image = test::load_sample_gray("boat", "img1.png");
  for (Mode mode : kEveryMode) {
    const ExtractorOptions options = options_for_mode(mode);
    const Features unmasked = extract(view_of(image), options);
    for (int value : {255, 1}) {
      const cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(value));
      EXPECT_TRUE(same_bytes(unmasked, extract_masked(image, mask, options)))
          << to_string(mode) << ", mask value " << value;
    }
  }
}

TEST(DetectionMask, EveryKernelSetAndThreadCountGivesTheScalarBytes) {
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 5);
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  cv::circle(mask, {image.cols / 2, image.rows / 2}, image.rows / 3, cv::Scalar(7), cv::FILLED);
  std::mt19937 rng(11);
  for (int i = 0; i < 12; ++i) {  // ragged holes and islands, to cross block and word edges
    const int x = static_cast<int>(rng() % static_cast<unsigned>(image.cols - 60)),
              y = static_cast<int>(rng() % static_cast<unsigned>(image.rows - 60));
    mask(cv::Rect(x, y, 1 + static_cast<int>(rng() % 59), 1 + static_cast<int>(rng() % 59)))
        .setTo(i % 2 ? 255 : 0);
  }
  for (Mode mode : kEveryMode) {
    ExtractorOptions reference_options = options_for_mode(mode);
    reference_options.kernels = KernelSet::scalar;
    reference_options.threads = 1;
    const Features reference = extract_masked(image, mask, reference_options);
    ASSERT_GT(reference.keypoints.size(), 100u);
    for (const Keypoint& kp : reference.keypoints)
      ASSERT_TRUE(allowed_at(mask, kp)) << to_string(mode);
    for (KernelSet set : available_kernel_sets())
      for (int threads : {1, 2, 5}) {
        ExtractorOptions options = reference_options;
        options.kernels = set;
        options.threads = threads;
        EXPECT_TRUE(same_bytes(reference, extract_masked(image, mask, options)))
            << to_string(mode) << ", " << to_string(set) << " at " << threads << " thread(s)";
      }
  }
}

TEST(DetectionMask, AMaskOfAnotherSizeIsAnError) {
  const cv::Mat image = test::load_sample_gray("boat", "img1.png");
  const cv::Mat mask(image.rows, image.cols - 1, CV_8UC1, cv::Scalar(255));
  try {
    extract_masked(image, mask, ExtractorOptions{});
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not the image's size"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aief

// Detection on a smoothed level (core/detection/detection_smoothing.hpp,
// core/kernels/binomial5_row.hpp): the row kernel against a direct 5x5 oracle on random odd sizes,
// the passes a sigma runs, that the option is off in every mode but quality and refused out of
// range, that descriptors and angles stay the level's own, that it finds more correct matches
// against a heavily blurred copy, and every kernel set and thread count. The option across the
// whole option space is tests/test_pipeline_differential.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "aief/match.hpp"
#include "core/detection/detection_smoothing.hpp"
#include "core/kernels/binomial5_row.hpp"
#include "core/kernels/kernel_table.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

ImageView view_of_mat(const cv::Mat& image) {
  return ImageView{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
}

// The kernel's formula written directly: 25 taps, replicated borders by clamping each tap.
std::uint8_t binomial_oracle(const cv::Mat& image, int x, int y) {
  static constexpr int kTaps[5] = {1, 4, 6, 4, 1};
  int sum = 0;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      sum += kTaps[j] * kTaps[i] *
             image.at<std::uint8_t>(std::clamp(y + j - 2, 0, image.rows - 1),
                                    std::clamp(x + i - 2, 0, image.cols - 1));
  return static_cast<std::uint8_t>((sum + 128) >> 8);
}

TEST(DetectionSmoothing, RowKernelIsTheDirectBinomialBlur) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 6; ++trial) {
    const int width = 1 + static_cast<int>(rng() % 97), height = 1 + static_cast<int>(rng() % 41);
    const cv::Mat image = test::random_image(width, height, rng());
    std::vector<std::uint16_t> sums(static_cast<std::size_t>(width) + 4);
    std::vector<std::uint8_t> row(static_cast<std::size_t>(width));
    for (int y = 0; y < height; ++y) {
      binomial5_row_scalar(view_of_mat(image), y, sums.data(), row.data());
      for (int x = 0; x < width; ++x)
        ASSERT_EQ(row[static_cast<std::size_t>(x)], binomial_oracle(image, x, y))
            << width << "x" << height << " at (" << x << ", " << y << ")";
    }
  }
}

TEST(DetectionSmoothing, SigmaRunsItsSquareInPassesAtLeastOne) {
  EXPECT_EQ(detection_smoothing_passes(0), 0);
  EXPECT_EQ(detection_smoothing_passes(0.3), 1);
  EXPECT_EQ(detection_smoothing_passes(1), 1);
  EXPECT_EQ(detection_smoothing_passes(1.5), 2);
  EXPECT_EQ(detection_smoothing_passes(2), 4);
  EXPECT_EQ(detection_smoothing_passes(3), 9);
}

// Each pass count has one value (core/options/detection_smoothing_values.hpp): another sigma that
// runs the same passes is refused, naming the value that does, so two option records that differ
// never hold the same bytes (before: 1e-320, 0.01, 0.5 and 1.2 ran 1.0's one pass but recorded
// themselves, and reruns and merges took them for other options).
TEST(DetectionSmoothing, EachPassCountHasOneValueAndAnotherSigmaIsRefused) {
  const double values[] = {1, 1.5, 1.8, 2, 2.3, 2.5, 2.7, 2.9, 3};
  for (int passes = 1; passes <= 9; ++passes) {
    const double value = detection_smoothing_of_passes(passes);
    EXPECT_EQ(value, values[passes - 1]) << passes;
    EXPECT_EQ(detection_smoothing_passes(value), passes) << value;
    ExtractorOptions options;
    options.detection_smoothing = value;
    EXPECT_NO_THROW(options.validate()) << value;
  }
  EXPECT_NO_THROW(ExtractorOptions{}.validate());  // 0: none
  EXPECT_NO_THROW(options_for_mode(Mode::quality).validate());
  const struct {
    double sigma;
    std::string named;
  } refused[] = {{1e-320, "runs 1 pass of the 5x5 binomial, as 1 does"},
                 {0.01, "as 1 does"},
                 {0.5, "as 1 does"},
                 {1.2, "as 1 does"},
                 {std::sqrt(2.0), "runs 2 passes of the 5x5 binomial, as 1.5 does"},
                 {1.3, "as 1.5 does"},
                 {2.1, "as 2 does"}};
  for (const auto& r : refused) {
    ExtractorOptions options;
    options.detection_smoothing = r.sigma;
    try {
      options.validate();
      ADD_FAILURE() << r.sigma << " accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(r.named), std::string::npos) << message;
      EXPECT_NE(message.find("0 (none), 1, 1.5, 1.8, 2, 2.3, 2.5, 2.7, 2.9, 3"), std::string::npos)
          << message;
    }
  }
}

// Two passes run in bands of rows (core/detection/detection_smoothing.cpp): heights around the
// band's size and its multiples, every kernel set, against one pass run on one pass's whole image.
TEST(DetectionSmoothing, TwoPassesAreOnePassOfOnePass) {
  const KernelTable& scalar = kernel_table(KernelSet::scalar);
  for (int height : {5, 35, 36, 37, 61, 64, 66, 67, 97, 131}) {
    const cv::Mat image = test::random_textured_image(83, height, 7);
    SmoothingScratch scratch;
    GrayImage once, again;
    smooth_for_detection(view_of_mat(image), 1, scalar, scratch, once);
    smooth_for_detection(once.view(), 1, scalar, scratch, again);
    for (KernelSet set : available_kernel_sets()) {
      GrayImage twice;
      smooth_for_detection(view_of_mat(image), 2, kernel_table(set), scratch, twice);
      ASSERT_EQ(twice.width(), 83);
      ASSERT_EQ(twice.height(), height);
      EXPECT_EQ(std::memcmp(twice.data(), again.data(), static_cast<std::size_t>(83 * height)), 0)
          << to_string(set) << ", height " << height;
    }
  }
}

TEST(DetectionSmoothing, OffInEveryModeButQualityAndRefusedOutOfRange) {
  for (Mode mode :
       {Mode::aief, Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy, Mode::faithful})
    EXPECT_EQ(options_for_mode(mode).detection_smoothing, 0.0) << to_string(mode);
  const ExtractorOptions quality = options_for_mode(Mode::quality);
  EXPECT_EQ(quality.detection_smoothing, 1.5);
  EXPECT_EQ(quality.scale_factor, 1.1);
  EXPECT_EQ(quality.n_levels, 18);
  EXPECT_EQ(quality.descriptor, DescriptorKind::box);
  // No entropy mask: it kept ~95% of the hard families' blocks and changed no match
  // (docs/design.md §11, docs/evaluation.md "Precision").
  EXPECT_EQ(quality.entropy, EntropyMeasure::off);
  ExtractorOptions options;
  options.detection_smoothing = 3.5;
  EXPECT_THROW(options.validate(), Error);
  options.detection_smoothing = -1;
  EXPECT_THROW(options.validate(), Error);
}

// The keypoints FAST finds on the smoothed levels, described again without smoothing (the level
// itself): the same angles and descriptors, so only detection reads the smoothed copy.
TEST(DetectionSmoothing, AnglesAndDescriptorsAreTheLevelsOwn) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  ExtractorOptions options;
  options.kernels = KernelSet::scalar;
  options.detection_smoothing = 1.5;
  const Features smoothed = Extractor(options).extract(view_of_mat(image));
  ASSERT_GT(smoothed.keypoints.size(), 900u);
  options.detection_smoothing = 0;
  const Features plain = Extractor(options).extract(view_of_mat(image));
  int moved = 0;
  for (std::size_t i = 0; i < std::min(plain.keypoints.size(), smoothed.keypoints.size()); ++i)
    moved += plain.keypoints[i].x != smoothed.keypoints[i].x;
  EXPECT_GT(moved, 100) << "smoothing changed no keypoint: the test sees nothing";
  const Features described = Extractor(options).describe(view_of_mat(image), smoothed.keypoints);
  ASSERT_EQ(described.keypoints.size(), smoothed.keypoints.size());
  for (std::size_t i = 0; i < described.keypoints.size(); ++i) {
    EXPECT_EQ(described.keypoints[i].angle_deg, smoothed.keypoints[i].angle_deg) << i;
    EXPECT_EQ(described.descriptors[i], smoothed.descriptors[i]) << i;
  }
}

// Correct matches (within 3 px) from graf img1 to a copy rotated 10 degrees and blurred at sigma
// 4 (the heavy_blur family of scripts/make_synthetic_pairs.py --families).
int correct_matches_against_blur(const ExtractorOptions& options) {
  const cv::Mat sharp = test::load_sample_gray("graf", "img1.png");
  const cv::Mat turn = cv::getRotationMatrix2D({sharp.cols / 2.0f, sharp.rows / 2.0f}, 10, 1.0);
  cv::Mat warped, blurred;
  cv::warpAffine(sharp, warped, turn, sharp.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  cv::GaussianBlur(warped, blurred, cv::Size(0, 0), 4.0);
  Extractor extractor(options);
  const Features a = extractor.extract(view_of_mat(sharp)),
                 b = extractor.extract(view_of_mat(blurred));
  int correct = 0;
  for (const Match& m : match_descriptors(a.descriptors, b.descriptors, MatchOptions{})) {
    const Keypoint& p = a.keypoints[static_cast<std::size_t>(m.query)];
    const Keypoint& q = b.keypoints[static_cast<std::size_t>(m.train)];
    const double x =
        turn.at<double>(0, 0) * p.x + turn.at<double>(0, 1) * p.y + turn.at<double>(0, 2);
    const double y =
        turn.at<double>(1, 0) * p.x + turn.at<double>(1, 1) * p.y + turn.at<double>(1, 2);
    correct += std::hypot(x - q.x, y - q.y) <= 3.0;
  }
  return correct;
}

TEST(DetectionSmoothing, FindsMoreCorrectMatchesAgainstHeavyBlur) {
  ExtractorOptions options;
  const int plain = correct_matches_against_blur(options);
  options.detection_smoothing = 1.5;
  const int smoothed = correct_matches_against_blur(options);
  EXPECT_GT(smoothed, plain * 5 / 4) << "plain " << plain << ", smoothed " << smoothed;
}

TEST(DetectionSmoothing, EveryKernelSetAndThreadCountGivesTheScalarBytes) {
  std::vector<cv::Mat> images = {test::load_sample_gray("boat", "img1.png"),
                                 test::random_textured_image(203, 117, 5)};
  for (const cv::Mat& image : images)
    for (double sigma : {1.0, 1.5, 2.0}) {
      ExtractorOptions options = options_for_mode(Mode::quality);
      options.detection_smoothing = sigma;
      options.kernels = KernelSet::scalar;
      options.threads = 1;
      const Features reference = Extractor(options).extract(view_of_mat(image));
      for (KernelSet set : available_kernel_sets())
        for (int threads : {1, 2}) {
          options.kernels = set;
          options.threads = threads;
          const Features other = Extractor(options).extract(view_of_mat(image));
          ASSERT_EQ(other.keypoints.size(), reference.keypoints.size());
          for (std::size_t i = 0; i < reference.keypoints.size(); ++i) {
            ASSERT_EQ(std::memcmp(&other.keypoints[i], &reference.keypoints[i], sizeof(Keypoint)),
                      0)
                << to_string(set) << " at " << threads << " threads, keypoint " << i;
            ASSERT_EQ(other.descriptors[i], reference.descriptors[i]);
          }
        }
    }
}

}  // namespace
}  // namespace aief

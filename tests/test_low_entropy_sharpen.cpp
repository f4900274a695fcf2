// Sharpened low-entropy blocks (core/entropy/low_entropy_sharpen.hpp,
// core/kernels/unsharp_row.hpp): the row kernel against a direct 5x5 oracle on random odd sizes,
// the amount rule, the amounts' continuity across block borders (no seam for FAST), what the option
// does to a weak-texture half and that descriptors stay the unsharpened level's, every kernel set
// and thread count on real and random odd-size images, tiny and one-block images. The option across
// the whole option space is tests/test_pipeline_differential.cpp.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/entropy/low_entropy_sharpen.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/unsharp_row.hpp"
#include "simd/kernels.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

ImageView view_of_mat(const cv::Mat& image) {
  return ImageView{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
}

// The kernel's formula written directly: 25 taps, 64-bit, floor by std::floor of a double (exact
// at these magnitudes), replicated borders by clamping each tap.
std::uint8_t unsharp_oracle(const cv::Mat& image, int x, int y, int amount_q8) {
  static constexpr int kTaps[5] = {1, 4, 6, 4, 1};
  std::int64_t blur = 0;
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i) {
      const int xx = std::clamp(x + i, 0, image.cols - 1),
                yy = std::clamp(y + j, 0, image.rows - 1);
      blur += kTaps[i + 2] * kTaps[j + 2] * image.at<std::uint8_t>(yy, xx);
    }
  const int p = image.at<std::uint8_t>(y, x);
  const double added = std::floor((amount_q8 * (256.0 * p - blur) + 32768.0) / 65536.0);
  return static_cast<std::uint8_t>(std::clamp(p + static_cast<int>(added), 0, 255));
}

TEST(UnsharpRow, EqualsTheDirectFormulaOnRandomOddSizes) {
  std::mt19937 rng(2024);
  for (int width : {1, 2, 3, 5, 7, 15, 17, 31, 33, 63, 65, 127, 129}) {
    for (int height : {1, 2, 3, 4, 5, 9}) {
      const cv::Mat image = test::random_image(width, height, rng());
      std::vector<std::int16_t> amounts(static_cast<std::size_t>(width));
      std::vector<std::uint16_t> sums(static_cast<std::size_t>(width) + 4);
      std::vector<std::uint8_t> row(static_cast<std::size_t>(width));
      for (int y = 0; y < height; ++y) {
        for (std::int16_t& a : amounts)
          a = static_cast<std::int16_t>(std::uniform_int_distribution<int>(0, 512)(rng));
        if (y == 0) amounts[0] = 512;  // the extremes
        unsharp_row_scalar(view_of_mat(image), y, amounts.data(), sums.data(), row.data());
        for (int x = 0; x < width; ++x)
          ASSERT_EQ(row[static_cast<std::size_t>(x)],
                    unsharp_oracle(image, x, y, amounts[static_cast<std::size_t>(x)]))
              << width << "x" << height << " at " << x << "," << y;
      }
    }
  }
}

TEST(UnsharpRow, AmountZeroAndFlatImagesAreUnchanged) {
  const cv::Mat image = test::random_image(37, 11, 7);
  std::vector<std::int16_t> zero(37, 0), full(37, 512);
  std::vector<std::uint16_t> sums(41);
  std::vector<std::uint8_t> row(37);
  for (int y = 0; y < 11; ++y) {
    unsharp_row_scalar(view_of_mat(image), y, zero.data(), sums.data(), row.data());
    for (int x = 0; x < 37; ++x)
      ASSERT_EQ(row[static_cast<std::size_t>(x)], image.at<std::uint8_t>(y, x));
  }
  const cv::Mat flat(11, 37, CV_8U, cv::Scalar(93));
  unsharp_row_scalar(view_of_mat(flat), 5, full.data(), sums.data(), row.data());
  for (std::uint8_t v : row) EXPECT_EQ(v, 93);
}

TEST(LowEntropySharpen, AmountFallsLinearlyFromTwoAtZeroBitsToNoneAtSixBits) {
  EXPECT_EQ(sharpen_amount_q8(0.0), 512);
  EXPECT_EQ(sharpen_amount_q8(3.0), 256);
  EXPECT_EQ(sharpen_amount_q8(6.0), 0);
  EXPECT_EQ(sharpen_amount_q8(7.5), 0);
  int previous = 512;
  for (int q = 0; q <= 8 * 256; ++q) {
    const int amount = sharpen_amount_q8(q / 256.0);
    EXPECT_LE(amount, previous);
    previous = amount;
  }
}

// Blocks of 0 and 2 alternating like a checkerboard: between two block centres the amount moves
// from one block's to the other's a pixel at a time (no step at the border between them), and it
// is the block's own at its centre.
TEST(LowEntropySharpen, AmountIsContinuousAcrossBlockBordersAndTheBlocksOwnAtItsCentre) {
  for (int block : {8, 13, 32}) {
    const int width = 7 * block + 5, height = 5 * block + 3;
    const BlockGrid grid = make_block_grid(width, height, block);
    SharpenScratch scratch;
    scratch.block_amounts.resize(static_cast<std::size_t>(grid.count()));
    for (int r = 0; r < grid.rows(); ++r)
      for (int c = 0; c < grid.cols(); ++c)
        scratch.block_amounts[static_cast<std::size_t>(r * grid.cols() + c)] =
            (r + c) % 2 ? 512 : 0;
    prepare_sharpen_columns(grid, width, scratch);
    int narrowest = width;
    for (int c = 0; c < grid.cols(); ++c)
      narrowest = std::min(narrowest, grid.col_edges[c + 1] - grid.col_edges[c]);
    for (int r = 0; r < grid.rows(); ++r)
      narrowest = std::min(narrowest, grid.row_edges[r + 1] - grid.row_edges[r]);
    // The slope (centres at least `narrowest` apart), plus the weights' floor in 1/64: two steps
    // of 512 / 64 (the last pixel before a centre and the rounding).
    const int largest_step = 512 / narrowest + 2 * 512 / 64 + 1;
    std::vector<std::int16_t> previous_row;
    for (int y = 0; y < height; ++y) {
      sharpen_block_column_amounts(grid, y, scratch);
      sharpen_amount_row(grid, scratch);
      const std::vector<std::int16_t>& row = scratch.amount_row;
      for (int x = 0; x + 1 < width; ++x)
        ASSERT_LE(std::abs(row[x + 1] - row[x]), largest_step)
            << "block " << block << " at " << x << "," << y;
      if (!previous_row.empty()) {
        for (int x = 0; x < width; ++x)
          ASSERT_LE(std::abs(row[x] - previous_row[x]), largest_step)
              << "block " << block << " at " << x << "," << y;
      }
      previous_row = row;
    }
    // At the centre pixel of a block whose span is odd, the weight is exactly 0: its own amount.
    for (int r = 0; r < grid.rows(); ++r)
      for (int c = 0; c < grid.cols(); ++c) {
        const int x0 = grid.col_edges[c], x1 = grid.col_edges[c + 1];
        const int y0 = grid.row_edges[r], y1 = grid.row_edges[r + 1];
        if ((x1 - x0) % 2 == 0 || (y1 - y0) % 2 == 0) continue;
        sharpen_block_column_amounts(grid, (y0 + y1 - 1) / 2, scratch);
        sharpen_amount_row(grid, scratch);
        EXPECT_EQ(scratch.amount_row[static_cast<std::size_t>((x0 + x1 - 1) / 2)],
                  scratch.block_amounts[static_cast<std::size_t>(r * grid.cols() + c)]);
      }
  }
}

// A weak texture (smoothed noise in 60 gray levels) under blocks whose amounts alternate 0 and 2
// like a checkerboard. With each block at its own amount (the step the blending avoids), FAST's
// corners crowd along the block borders; with the blended amounts they lie there no more often
// than without sharpening.
TEST(LowEntropySharpen, BlendedAmountsPutNoMoreCornersAtBlockBordersThanNoSharpening) {
  const int width = 640, height = 480;
  cv::Mat texture;  // noise smoothed at sigma 2: fewer, larger blobs than random_textured_image's
  cv::GaussianBlur(test::random_image(width, height, 3), texture, cv::Size(0, 0), 2.0);
  cv::normalize(texture, texture, 60, 120, cv::NORM_MINMAX);
  const BlockGrid grid = make_block_grid(width, height, 32);
  std::vector<double> entropies(static_cast<std::size_t>(grid.count()));
  for (int r = 0; r < grid.rows(); ++r)
    for (int c = 0; c < grid.cols(); ++c)
      entropies[static_cast<std::size_t>(r * grid.cols() + c)] = (r + c) % 2 ? 0.0 : 8.0;
  SharpenScratch scratch;
  GrayImage blended;
  ASSERT_TRUE(sharpen_low_entropy_blocks(view_of_mat(texture), grid, entropies,
                                         kernel_table(KernelSet::scalar), scratch, blended));
  cv::Mat stepped(height, width, CV_8U);
  std::vector<std::int16_t> amounts(static_cast<std::size_t>(width));
  std::vector<std::uint16_t> sums(static_cast<std::size_t>(width) + 4);
  for (int y = 0; y < height; ++y) {
    const int inside_y = std::clamp(y, kEdgeBorder, height - kEdgeBorder - 1);
    for (int x = 0; x < width; ++x) {
      const int inside_x = std::clamp(x, kEdgeBorder, width - kEdgeBorder - 1);
      amounts[static_cast<std::size_t>(x)] = static_cast<std::int16_t>(sharpen_amount_q8(
          entropies[static_cast<std::size_t>(block_of(grid, inside_x, inside_y))]));
    }
    unsharp_row_scalar(view_of_mat(texture), y, amounts.data(), sums.data(), stepped.ptr(y));
  }
  // The share of FAST corners (at the retry threshold, 7) within one pixel of a block border.
  const auto near_edges = [](const std::vector<int>& edges, int p) {
    for (int e : edges)
      if (std::abs(p - e) <= 1) return true;
    return false;
  };
  const auto border_share = [&](const cv::Mat& image) {
    std::vector<cv::KeyPoint> found;
    cv::FAST(image, found, 7, true);
    int inside = 0, near = 0;
    for (const cv::KeyPoint& k : found) {
      const int x = static_cast<int>(k.pt.x), y = static_cast<int>(k.pt.y);
      if (x < kEdgeBorder || x >= width - kEdgeBorder || y < kEdgeBorder ||
          y >= height - kEdgeBorder)
        continue;
      ++inside;
      near +=
          near_edges(std::vector<int>(grid.col_edges.begin() + 1, grid.col_edges.end() - 1), x) ||
          near_edges(std::vector<int>(grid.row_edges.begin() + 1, grid.row_edges.end() - 1), y);
    }
    EXPECT_GT(inside, 500);
    return static_cast<double>(near) / inside;
  };
  const double plain = border_share(texture), step = border_share(stepped),
               blend = border_share(cv::Mat(height, width, CV_8U, blended.data()));
  EXPECT_GT(step, plain + 0.02) << "the stepped amounts show no seam: the test sees nothing";
  EXPECT_LT(blend, plain + 0.01) << "plain " << plain << ", stepped " << step << ", blended "
                                 << blend;
}

// Left half: smoothed noise at full contrast. Right half: the same texture dark and weak (squeezed
// into 24 gray levels from 8): its blocks' entropy is low, few corners pass FAST's 20.
cv::Mat textured_left_dark_right(int width, int height) {
  cv::Mat image = test::random_textured_image(width, height, 25);
  for (int y = 0; y < height; ++y)
    for (int x = width / 2; x < width; ++x) {
      std::uint8_t& pixel = image.at<std::uint8_t>(y, x);
      pixel = static_cast<std::uint8_t>(8 + pixel * 24 / 255);
    }
  return image;
}

TEST(LowEntropySharpen, GivesTheDarkHalfMoreKeypointsWithTheUnsharpenedLevelsDescriptors) {
  const cv::Mat image = textured_left_dark_right(640, 480);
  for (Mode mode : {Mode::orbslam2, Mode::faithful}) {
    ExtractorOptions options = options_for_mode(mode);
    options.n_features = 2000;
    const Features plain = Extractor(options).extract(view_of_mat(image));
    options.low_entropy_sharpen = true;
    const Features sharpened = Extractor(options).extract(view_of_mat(image));
    int right_before = 0, right_after = 0;
    for (const Keypoint& k : plain.keypoints) right_before += k.x >= 320;
    for (const Keypoint& k : sharpened.keypoints) right_after += k.x >= 320;
    EXPECT_GT(right_after, right_before) << to_string(mode);
    // A keypoint both find (position, level, angle) has the same descriptor: the descriptor is
    // computed on the level as it is, not the sharpened copy.
    std::map<std::tuple<float, float, int, float>, std::size_t> plain_at;
    for (std::size_t i = 0; i < plain.keypoints.size(); ++i) {
      const Keypoint& k = plain.keypoints[i];
      plain_at[{k.x, k.y, k.octave, k.angle_deg}] = i;
    }
    int shared = 0;
    for (std::size_t i = 0; i < sharpened.keypoints.size(); ++i) {
      const Keypoint& k = sharpened.keypoints[i];
      const auto found = plain_at.find({k.x, k.y, k.octave, k.angle_deg});
      if (found == plain_at.end()) continue;
      ++shared;
      EXPECT_EQ(sharpened.descriptors[i], plain.descriptors[found->second]);
    }
    EXPECT_GT(shared, 100) << to_string(mode);
  }
}

// The keypoints and descriptors byte for byte; "" when equal.
std::string first_difference(const Features& a, const Features& b) {
  if (a.keypoints.size() != b.keypoints.size())
    return std::to_string(a.keypoints.size()) + " keypoints against " +
           std::to_string(b.keypoints.size());
  for (std::size_t i = 0; i < a.keypoints.size(); ++i)
    if (std::memcmp(&a.keypoints[i], &b.keypoints[i], sizeof(Keypoint)) != 0 ||
        a.descriptors[i] != b.descriptors[i])
      return "keypoint " + std::to_string(i);
  return "";
}

TEST(LowEntropySharpen, EveryKernelSetAndThreadCountGivesTheScalarBytes) {
  std::vector<cv::Mat> images = {test::load_sample_gray("graf", "img1.png"),
                                 test::load_sample_gray("leuven", "img2.png")};
  std::mt19937 rng(20261203);
  for (int i = 0; i < 3; ++i)  // odd sizes, block grids with a merged last column and row
    images.push_back(test::random_textured_image(101 + 2 * static_cast<int>(rng() % 300),
                                                 77 + 2 * static_cast<int>(rng() % 200), rng()));
  cv::Mat dark = images[0] * 0.2;  // every block low-entropy: the strongest amounts
  images.push_back(dark);
  for (Mode mode : {Mode::orbslam2, Mode::faithful, Mode::aief}) {
    for (const cv::Mat& image : images) {
      ExtractorOptions options = options_for_mode(mode);
      options.low_entropy_sharpen = true;
      options.kernels = KernelSet::scalar;
      options.threads = 1;
      const Features reference = Extractor(options).extract(view_of_mat(image));
      for (KernelSet set : available_kernel_sets())
        for (int threads : {1, 3}) {
          options.kernels = set;
          options.threads = threads;
          EXPECT_EQ(first_difference(reference, Extractor(options).extract(view_of_mat(image))), "")
              << to_string(mode) << ", " << to_string(set) << ", " << threads << " threads, "
              << image.cols << "x" << image.rows;
        }
    }
  }
}

TEST(LowEntropySharpen, TinyAndOneBlockImagesNeverFail) {
  for (const auto& [width, height, block] : std::vector<std::tuple<int, int, int>>{
           {39, 39, 8}, {39, 39, 1024}, {40, 97, 32}, {300, 39, 1024}}) {
    const cv::Mat image = test::random_textured_image(width, height, 3);
    for (Mode mode : {Mode::aief, Mode::orbslam2, Mode::faithful}) {
      ExtractorOptions options = options_for_mode(mode);
      options.block_size = block;
      options.low_entropy_sharpen = true;
      EXPECT_NO_THROW(Extractor(options).extract(view_of_mat(image))) << width << "x" << height;
    }
  }
  const cv::Mat too_small = test::random_textured_image(20, 20, 4);  // refused, named
  ExtractorOptions sharpened = options_for_mode(Mode::faithful);
  sharpened.low_entropy_sharpen = true;
  EXPECT_THROW(Extractor(sharpened).extract(view_of_mat(too_small)), Error);
  const cv::Mat flat(60, 60, CV_8U, cv::Scalar(0));  // every block 0 bits: the strongest amount
  ExtractorOptions options = options_for_mode(Mode::orbslam2);
  options.low_entropy_sharpen = true;
  EXPECT_TRUE(Extractor(options).extract(view_of_mat(flat)).keypoints.empty());
}

}  // namespace
}  // namespace aief

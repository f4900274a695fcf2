// Block histograms and their entropy (DESIGN.md section 1, paper Eq. 5-6): exact integer sums
// against a direct double computation, and the values the definitions fix.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/block_entropy.hpp"

namespace aief {
namespace {

double direct_histogram_entropy(const std::vector<std::uint8_t>& pixels) {
  double counts[256] = {};
  for (std::uint8_t p : pixels) counts[p] += 1;
  double h = 0;
  for (double c : counts)
    if (c > 0) h -= (c / pixels.size()) * std::log2(c / pixels.size());
  return h;
}

double direct_intensity_entropy(const std::vector<std::uint8_t>& pixels) {
  double sum = 0;
  for (std::uint8_t p : pixels) sum += p;
  if (sum == 0) return 0;
  double h = 0;
  for (std::uint8_t p : pixels)
    if (p > 0) h -= (p / sum) * std::log2(p / sum);
  return h;
}

std::vector<std::uint32_t> histogram_of(const std::vector<std::uint8_t>& pixels, int width, int height) {
  std::vector<std::uint32_t> hist(256, 0);
  accumulate_histogram_scalar(pixels.data(), width, width, height, hist.data());
  return hist;
}

TEST(BlockEntropy, MatchesADirectDoubleComputation) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const int width = 1 + static_cast<int>(rng() % 70), height = 1 + static_cast<int>(rng() % 70);
    const int levels = 1 + static_cast<int>(rng() % 256);  // few or many distinct values
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height);
    for (std::uint8_t& p : pixels) p = static_cast<std::uint8_t>(rng() % levels);
    const std::vector<std::uint32_t> hist = histogram_of(pixels, width, height);
    EXPECT_NEAR(histogram_entropy_bits(hist.data()), direct_histogram_entropy(pixels), 1e-6) << width << "x" << height;
    EXPECT_NEAR(intensity_entropy_bits(hist.data()), direct_intensity_entropy(pixels), 1e-6) << width << "x" << height;
  }
}

TEST(BlockEntropy, ValuesFixedByTheDefinition) {
  std::vector<std::uint8_t> flat(32 * 32, 77);
  EXPECT_EQ(histogram_entropy_bits(histogram_of(flat, 32, 32).data()), 0.0);
  for (int repeats : {1, 4}) {  // 16x16 with each value once, 32x32 with each value 4 times
    std::vector<std::uint8_t> all(256 * static_cast<std::size_t>(repeats));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint8_t>(i % 256);
    const int side = repeats == 1 ? 16 : 32;
    EXPECT_NEAR(histogram_entropy_bits(histogram_of(all, side, side).data()), 8.0, 1e-9);
  }
  std::vector<std::uint8_t> zeros(100, 0);
  EXPECT_EQ(intensity_entropy_bits(histogram_of(zeros, 10, 10).data()), 0.0);
  // Intensity variant of a uniform non-zero block: p = 1/n everywhere, log2(n) bits.
  std::vector<std::uint8_t> uniform(1024, 200);
  EXPECT_NEAR(intensity_entropy_bits(histogram_of(uniform, 32, 32).data()), 10.0, 1e-9);
  EXPECT_EQ(histogram_entropy_bits(std::vector<std::uint32_t>(256, 0).data()), 0.0);  // empty block
}

TEST(BlockEntropy, HistogramOfAStridedViewCountsOnlyTheView) {
  const int stride = 50, width = 37, height = 23;
  std::vector<std::uint8_t> image(static_cast<std::size_t>(stride) * height);
  std::mt19937 rng(9);
  for (std::uint8_t& p : image) p = static_cast<std::uint8_t>(rng());
  std::vector<std::uint32_t> hist(256, 5);  // accumulates onto what is there
  accumulate_histogram_scalar(image.data() + 3, stride, width, height - 1, hist.data());
  std::vector<std::uint32_t> expected(256, 5);
  for (int y = 0; y < height - 1; ++y)
    for (int x = 0; x < width; ++x) ++expected[image[static_cast<std::size_t>(y) * stride + 3 + x]];
  EXPECT_EQ(hist, expected);
}

TEST(BlockEntropy, MeasureSelection) {
  std::vector<std::uint8_t> pixels = {0, 10, 10, 200};
  const std::vector<std::uint32_t> hist = histogram_of(pixels, 4, 1);
  EXPECT_EQ(entropy_bits(hist.data(), EntropyMeasure::histogram), histogram_entropy_bits(hist.data()));
  EXPECT_EQ(entropy_bits(hist.data(), EntropyMeasure::intensity), intensity_entropy_bits(hist.data()));
}

}  // namespace
}  // namespace aief

// Block histograms and their entropy (docs/design.md §3, paper Eq. 5-6): exact integer sums
// against a direct double computation, and the values the definitions fix.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "aief/image.hpp"
#include "core/entropy/block_entropy.hpp"
#include "core/frame/frame_analysis.hpp"
#include "simd/kernels.hpp"

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

std::vector<std::uint32_t> histogram_of(const std::vector<std::uint8_t>& pixels, int width,
                                        int height) {
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
    EXPECT_NEAR(histogram_entropy_bits(hist.data()), direct_histogram_entropy(pixels), 1e-6)
        << width << "x" << height;
    EXPECT_NEAR(intensity_entropy_bits(hist.data()), direct_intensity_entropy(pixels), 1e-6)
        << width << "x" << height;
  }
}

TEST(BlockEntropy, ValuesFixedByTheDefinition) {
  std::vector<std::uint8_t> flat(32 * 32, 77);
  EXPECT_EQ(histogram_entropy_bits(histogram_of(flat, 32, 32).data()), 0.0);
  // Exactly 0 at any area, not only at powers of two (an edge block of 32 x 17; an image of
  // 200 x 200, past the table): a mask at F = 0 keeps no block of one gray level.
  for (const auto& [w, h] : {std::pair{32, 17}, std::pair{23, 31}, std::pair{200, 200}}) {
    std::vector<std::uint8_t> one_level(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
                                        9);
    EXPECT_EQ(histogram_entropy_bits(histogram_of(one_level, w, h).data()), 0.0) << w << " x " << h;
  }
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

// Entropies of the counts, straight from the definitions in long double (no fixed point).
long double exact_histogram_entropy(const std::vector<std::uint64_t>& counts) {
  long double n = 0, sum = 0;
  for (std::uint64_t c : counts) {
    n += static_cast<long double>(c);
    if (c > 1) sum += static_cast<long double>(c) * std::log2(static_cast<long double>(c));
  }
  return n == 0 ? 0 : std::log2(n) - sum / n;
}

long double exact_intensity_entropy(const std::vector<std::uint64_t>& counts) {
  long double s = 0, sum = 0;
  for (int k = 1; k < 256; ++k) {
    const long double c = static_cast<long double>(counts[static_cast<std::size_t>(k)]);
    s += c * k;
    sum += c * k * std::log2(static_cast<long double>(k));
  }
  return s == 0 ? 0 : std::log2(s) - sum / s;
}

TEST(BlockEntropy, ExactForTheLargestCountsABlockOrImageCanHold) {
  // One bright value filling the largest accepted image (2^26 pixels), and the largest block
  // (1535 x 1535: block_size 1024 plus a merged short last block): the intensity sum of c * k
  // log2 k passed 2^64 at about 2 Mpx of bright pixels, so these read 29.8 bits, not log2(n).
  for (std::uint64_t n :
       {static_cast<std::uint64_t>(kLargestMaxImagePixels), std::uint64_t{1535} * 1535}) {
    std::vector<std::uint32_t> hist(256, 0);
    hist[255] = static_cast<std::uint32_t>(n);
    EXPECT_NEAR(intensity_entropy_bits(hist.data()), std::log2(static_cast<double>(n)), 1e-9)
        << n << " pixels";
    EXPECT_EQ(histogram_entropy_bits(hist.data()), 0.0) << n << " pixels";
    // Spread over the bright half of the bins, with uneven counts.
    std::vector<std::uint64_t> counts(256, 0);
    for (int k = 128; k < 256; ++k)
      counts[static_cast<std::size_t>(k)] = n / 128 - static_cast<std::uint64_t>(k % 7);
    for (int k = 0; k < 256; ++k)
      hist[static_cast<std::size_t>(k)] =
          static_cast<std::uint32_t>(counts[static_cast<std::size_t>(k)]);
    EXPECT_NEAR(intensity_entropy_bits(hist.data()),
                static_cast<double>(exact_intensity_entropy(counts)), 1e-6)
        << n;
    EXPECT_NEAR(histogram_entropy_bits(hist.data()),
                static_cast<double>(exact_histogram_entropy(counts)), 1e-6)
        << n;
  }
}

TEST(BlockEntropy, ImageEntropyExactAtTheLargestAcceptedSizeUnderEveryKernelSet) {
  // 8192 x 8192 = max_image_pixels' upper bound, mostly saturated white (the worst case for
  // the intensity sums) with a textured square so the histogram measure is not trivial.
  constexpr int kSide = 8192;
  static_assert(static_cast<long long>(kSide) * kSide == kLargestMaxImagePixels);
  GrayImage image(kSide, kSide);
  std::fill_n(image.data(), static_cast<std::size_t>(kSide) * kSide, std::uint8_t{255});
  std::mt19937 rng(11);
  for (int y = 1000; y < 1600; ++y)
    for (int x = 2000; x < 2700; ++x)
      image.data()[static_cast<std::size_t>(y) * kSide + x] = static_cast<std::uint8_t>(rng());
  std::vector<std::uint64_t> counts(256, 0);
  for (std::size_t i = 0; i < static_cast<std::size_t>(kSide) * kSide; ++i)
    ++counts[image.data()[i]];

  for (EntropyMeasure measure : {EntropyMeasure::histogram, EntropyMeasure::intensity}) {
    const long double expected = measure == EntropyMeasure::histogram
                                     ? exact_histogram_entropy(counts)
                                     : exact_intensity_entropy(counts);
    ExtractorOptions options;
    options.entropy = measure;
    options.n_levels = 1;
    options.block_size = 1024;
    options.max_image_pixels = kLargestMaxImagePixels;
    for (KernelSet set : available_kernel_sets()) {
      FrameAnalysis analysis;
      analysis.start(image.view(), options, kernel_table(set));
      analysis.compute_entropies(0);
      EXPECT_NEAR(analysis.image_entropy_bits(), static_cast<double>(expected), 1e-6)
          << to_string(measure) << " under " << to_string(set);
      for (double block_bits : analysis.blocks(0).entropy_bits) {
        EXPECT_GE(block_bits, 0.0);
        EXPECT_LE(block_bits,
                  measure == EntropyMeasure::histogram ? 8.0 : std::log2(1535.0 * 1535.0));
      }
    }
  }
}

TEST(BlockEntropy, MeasureSelection) {
  std::vector<std::uint8_t> pixels = {0, 10, 10, 200};
  const std::vector<std::uint32_t> hist = histogram_of(pixels, 4, 1);
  EXPECT_EQ(entropy_bits(hist.data(), EntropyMeasure::histogram),
            histogram_entropy_bits(hist.data()));
  EXPECT_EQ(entropy_bits(hist.data(), EntropyMeasure::intensity),
            intensity_entropy_bits(hist.data()));
  EXPECT_EQ(entropy_bits(hist.data(), 4, EntropyMeasure::histogram),
            histogram_entropy_bits(hist.data()));
  EXPECT_EQ(entropy_bits(hist.data(), 4, EntropyMeasure::intensity),
            intensity_entropy_bits(hist.data()));
}

TEST(BlockEntropy, GivenPixelCountEqualsTheSummedOne) {
  // Blocks (counts in the table) and a histogram past the table's 4096 counts.
  for (const auto& [width, height] :
       {std::pair{32, 32}, std::pair{63, 47}, std::pair{1, 1}, std::pair{300, 200}}) {
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < pixels.size(); ++i)
      pixels[i] = static_cast<std::uint8_t>((i * 7919 + i / 13) % 97);
    const std::vector<std::uint32_t> hist = histogram_of(pixels, width, height);
    EXPECT_EQ(histogram_entropy_bits(hist.data(), pixels.size()),
              histogram_entropy_bits(hist.data()))
        << width << "x" << height;
  }
}

}  // namespace
}  // namespace aief

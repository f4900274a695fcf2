// Every kernel under every kernel set this CPU runs, bit for bit against the scalar reference,
// on seeded random images of sizes straddling the vector widths and on the bundled real images;
// and the whole pipeline at 1 and 2 threads under each set (simd/kernel_validation.hpp).
// Needs no OpenCV: the OpenCV-free and aarch64 builds run it on the bundled PGM crop, and a
// build with OpenCV adds the full-size PNG samples.
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/kernels/kernel_table.hpp"
#include "simd/kernel_validation.hpp"
#include "simd/kernels.hpp"
#include "tests/pgm_image.hpp"
#if AIEF_TEST_WITH_OPENCV
#include "tests/test_support.hpp"
#endif

namespace aief {
namespace {

std::vector<GrayImage> real_images() {
  std::vector<GrayImage> images;
  images.push_back(test::read_pgm(std::string(AIEF_SAMPLE_DIR) + "/graf/img1_center_320x240.pgm"));
#if AIEF_TEST_WITH_OPENCV
  for (const char* sequence : {"graf", "boat", "leuven"}) {
    const cv::Mat gray = test::load_sample_gray(sequence, "img1.png");
    GrayImage image(gray.cols, gray.rows);
    for (int y = 0; y < gray.rows; ++y)
      std::copy_n(gray.ptr<std::uint8_t>(y), gray.cols, image.data() + y * gray.cols);
    images.push_back(std::move(image));
  }
#endif
  return images;
}

class SimdKernels : public testing::TestWithParam<std::tuple<KernelSet, std::string>> {};

TEST_P(SimdKernels, IdenticalToScalarOnRandomImages) {
  const auto& [set, kernel] = GetParam();
  static const std::vector<GrayImage> images = validation_images();
  EXPECT_EQ(validate_kernel(kernel, set, images), "");
}

TEST_P(SimdKernels, IdenticalToScalarOnRealImages) {
  const auto& [set, kernel] = GetParam();
  static const std::vector<GrayImage> images = real_images();
  EXPECT_EQ(validate_kernel(kernel, set, images), "");
}

// Every SIMD set with every kernel. The scalar set only with "extract", where the other side is
// the pipeline at 2 threads: a scalar kernel checked against itself could never fail.
std::vector<std::tuple<KernelSet, std::string>> cases() {
  std::vector<std::tuple<KernelSet, std::string>> out;
  for (KernelSet set : available_kernel_sets())
    for (const std::string& kernel : validated_kernel_names())
      if (set != KernelSet::scalar || kernel == "extract") out.emplace_back(set, kernel);
  return out;
}

INSTANTIATE_TEST_SUITE_P(Sets, SimdKernels, testing::ValuesIn(cases()),
                         [](const testing::TestParamInfo<SimdKernels::ParamType>& info) {
                           std::string set(to_string(std::get<0>(info.param)));
                           for (char& c : set)
                             if (c == '.') c = '_';
                           return set + "_" + std::get<1>(info.param);
                         });

// Histogram kernels may count in narrow (16-bit) banks and fold them before they overflow: one
// gray level over many more pixels than 65535, in blocks, tall images and rows longer than a
// fold, counted exactly by every set. The expected counts are known without any kernel.
TEST(HistogramKernels, ExactPastSixteenBitCounters) {
  struct Case {
    int width, height;
  };
  for (const Case size :
       {Case{256, 256}, Case{600, 600}, Case{300001, 1}, Case{65535 * 4 + 3, 2}, Case{17, 20000}}) {
    const std::ptrdiff_t stride = size.width + 5;
    std::vector<std::uint8_t> pixels(
        static_cast<std::size_t>(stride) * static_cast<std::size_t>(size.height), 200);
    // Every pixel is 200 except one column of 7s and the padding past each row, which is 0.
    for (int y = 0; y < size.height; ++y) {
      pixels[static_cast<std::size_t>(y * stride + size.width / 2)] = 7;
      for (std::ptrdiff_t x = size.width; x < stride; ++x)
        pixels[static_cast<std::size_t>(y * stride + x)] = 0;
    }
    const std::uint32_t area =
        static_cast<std::uint32_t>(size.width) * static_cast<std::uint32_t>(size.height);
    for (KernelSet set : available_kernel_sets()) {
      std::vector<std::uint32_t> hist(256, 1);  // accumulates onto what is there
      kernel_table(set).accumulate_histogram(pixels.data(), stride, size.width, size.height,
                                             hist.data());
      std::vector<std::uint32_t> expected(256, 1);
      expected[200] += area - static_cast<std::uint32_t>(size.height);
      expected[7] += static_cast<std::uint32_t>(size.height);
      EXPECT_EQ(hist, expected) << to_string(set) << " " << size.width << "x" << size.height;
    }
  }
}

TEST(KernelDispatch, NoCaseComparesTheScalarKernelsWithThemselves) {
  for (const auto& [set, kernel] : cases())
    EXPECT_TRUE(set != KernelSet::scalar || kernel == "extract")
        << "scalar " << kernel << " against scalar " << kernel;
}

TEST(KernelDispatch, ScalarAlwaysAvailableAndUnknownSetsRefused) {
  const std::vector<KernelSet> sets = available_kernel_sets();
  ASSERT_FALSE(sets.empty());
  EXPECT_EQ(sets.front(), KernelSet::scalar);
  EXPECT_EQ(best_kernel_set(), sets.back());
  EXPECT_STREQ(kernel_table(KernelSet::scalar).name, "scalar");
  EXPECT_EQ(kernel_table(KernelSet::auto_select).set, default_kernel_set());
}

// Validation and benchmarks are made from the one kernel list: every listed kernel is validated,
// in table order, and the whole pipeline after them.
TEST(KernelDispatch, ValidationCoversTheKernelList) {
  std::vector<std::string> expected(std::begin(kKernelNames), std::end(kKernelNames));
  expected.emplace_back("extract");
  EXPECT_EQ(validated_kernel_names(), expected);
}

// What --print-kernels shows: scalar everywhere in the scalar table, each SIMD table's own code,
// and in the AVX-512 table the six 512-bit kernels beside the 256-bit ones it shares with AVX2
// (plus the VPOPCNTDQ Hamming kernel where the CPU has it).
TEST(KernelDispatch, EveryEntryNamesItsCode) {
  for (KernelSet set : available_kernel_sets()) {
    const KernelTable& table = kernel_table(set);
    int wide = 0;
    for (int k = 0; k < kKernelCount; ++k) {
      const std::string variant = kernel_variant(table, k);
      const std::string kernel = kKernelNames[k];
      SCOPED_TRACE(std::string(to_string(set)) + " " + kernel + ": " + variant);
      switch (set) {
        case KernelSet::scalar: EXPECT_EQ(variant, "scalar"); break;
        case KernelSet::sse4_2: EXPECT_EQ(variant, "sse4.2 128-bit"); break;
        case KernelSet::avx2: EXPECT_EQ(variant, "avx2 256-bit"); break;
        case KernelSet::neon64:
          EXPECT_EQ(variant, kernel == "positions_within_bounds" ? "scalar" : "neon64 128-bit");
          break;
        case KernelSet::avx512bw:
          if (kernel == "hamming_256_blocked") {
            EXPECT_TRUE(variant == "avx512vpopcntdq 512-bit" || variant == "avx512bw 256-bit");
          } else if (variant == "avx512bw 512-bit") {
            ++wide;
          } else {
            EXPECT_EQ(variant, "avx512bw 256-bit");
          }
          break;
        default: ADD_FAILURE() << "unexpected set";
      }
    }
    if (set == KernelSet::avx512bw) {
      EXPECT_EQ(wide, 6);
    }
  }
}

// AIEF_KERNELS decides what `auto` stands for, for the whole process, without code; it is read
// whenever a table for `auto` is asked for (an extractor is built).
class ForcedKernels : public testing::Test {
 protected:
  void TearDown() override { unsetenv(kKernelsEnvironmentVariable); }
  static void force(const char* value) { setenv(kKernelsEnvironmentVariable, value, 1); }
};

TEST_F(ForcedKernels, ScalarForcesTheScalarTableOnEveryDefaultExtractor) {
  force("scalar");
  EXPECT_EQ(default_kernel_set(), KernelSet::scalar);
  EXPECT_EQ(Extractor(ExtractorOptions{}).kernel_name(), "scalar");
}

TEST_F(ForcedKernels, EveryAvailableSetCanBeForced) {
  for (KernelSet set : available_kernel_sets()) {
    force(std::string(to_string(set)).c_str());
    EXPECT_EQ(kernel_table(KernelSet::auto_select).set, set) << to_string(set);
  }
}

TEST_F(ForcedKernels, AutoAndEmptyMeanTheBestSet) {
  force("auto");
  EXPECT_EQ(default_kernel_set(), best_kernel_set());
  force("");
  EXPECT_EQ(default_kernel_set(), best_kernel_set());
}

TEST_F(ForcedKernels, AnExplicitSetIsNotOverridden) {
  force(std::string(to_string(best_kernel_set())).c_str());
  ExtractorOptions options;
  options.kernels = KernelSet::scalar;
  EXPECT_EQ(Extractor(options).kernel_name(), "scalar");
}

void expect_refused(const char* value, const std::string& reason) {
  try {
    (void)Extractor(ExtractorOptions{});
    ADD_FAILURE() << "AIEF_KERNELS=" << value << " was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(std::string("AIEF_KERNELS=") + value), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
  }
}

// A forced set that silently did not apply would defeat the purpose: an unknown name or a set
// this CPU or build cannot run is an error naming the variable, not a quiet fallback.
TEST_F(ForcedKernels, UnknownOrUnavailableSetsAreRefused) {
  force("avx3");
  expect_refused("avx3", "unknown kernel set");
#if defined(__aarch64__)
  const char* foreign = "avx2";
#else
  const char* foreign = "neon64";
#endif
  force(foreign);
  expect_refused(foreign, "cannot run kernel set");
}

}  // namespace
}  // namespace aief

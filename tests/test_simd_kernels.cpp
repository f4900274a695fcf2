// Every kernel under every kernel set this CPU runs, bit for bit against the scalar reference,
// on seeded random images of sizes straddling the vector widths and on the bundled real images;
// and the whole pipeline at 1 and 2 threads under each set (simd/kernel_validation.hpp).
// Needs no OpenCV: the OpenCV-free and aarch64 builds run it on the bundled PGM crop, and a
// build with OpenCV adds the full-size PNG samples.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

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
    for (int y = 0; y < gray.rows; ++y) std::copy_n(gray.ptr<std::uint8_t>(y), gray.cols, image.data() + y * gray.cols);
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
  for (const Case size : {Case{256, 256}, Case{600, 600}, Case{300001, 1}, Case{65535 * 4 + 3, 2}, Case{17, 20000}}) {
    const std::ptrdiff_t stride = size.width + 5;
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(stride) * static_cast<std::size_t>(size.height), 200);
    // Every pixel is 200 except one column of 7s and the padding past each row, which is 0.
    for (int y = 0; y < size.height; ++y) {
      pixels[static_cast<std::size_t>(y * stride + size.width / 2)] = 7;
      for (std::ptrdiff_t x = size.width; x < stride; ++x) pixels[static_cast<std::size_t>(y * stride + x)] = 0;
    }
    const std::uint32_t area = static_cast<std::uint32_t>(size.width) * static_cast<std::uint32_t>(size.height);
    for (KernelSet set : available_kernel_sets()) {
      std::vector<std::uint32_t> hist(256, 1);  // accumulates onto what is there
      kernel_table(set).accumulate_histogram(pixels.data(), stride, size.width, size.height, hist.data());
      std::vector<std::uint32_t> expected(256, 1);
      expected[200] += area - static_cast<std::uint32_t>(size.height);
      expected[7] += static_cast<std::uint32_t>(size.height);
      EXPECT_EQ(hist, expected) << to_string(set) << " " << size.width << "x" << size.height;
    }
  }
}

TEST(KernelDispatch, NoCaseComparesTheScalarKernelsWithThemselves) {
  for (const auto& [set, kernel] : cases())
    EXPECT_TRUE(set != KernelSet::scalar || kernel == "extract") << "scalar " << kernel << " against scalar " << kernel;
}

TEST(KernelDispatch, ScalarAlwaysAvailableAndUnknownSetsRefused) {
  const std::vector<KernelSet> sets = available_kernel_sets();
  ASSERT_FALSE(sets.empty());
  EXPECT_EQ(sets.front(), KernelSet::scalar);
  EXPECT_EQ(best_kernel_set(), sets.back());
  EXPECT_STREQ(kernel_table(KernelSet::scalar).name, "scalar");
  EXPECT_EQ(kernel_table(KernelSet::auto_select).set, best_kernel_set());
}

}  // namespace
}  // namespace aief

// No allocation per frame after the first at a fixed image size: every buffer of the pipeline
// lives in the Extractor and is reused. Counted with a replaced global operator new.
#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "aief/extractor.hpp"
#include "tests/test_support.hpp"

namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace aief {
namespace {

long long allocations_of_third_frame(ExtractorOptions options, const cv::Mat& gray) {
  Extractor extractor(options);
  Features features;
  extractor.extract(view_of(gray), features);
  extractor.extract(view_of(gray), features);
  const long long before = g_allocations.load();
  extractor.extract(view_of(gray), features);
  return g_allocations.load() - before;
}

TEST(Allocations, NoneAfterTheFirstFramesOfOneSize) {
  const cv::Mat gray = test::load_sample_gray("graf", "img1.png");
  for (Mode mode : {Mode::aief, Mode::orbslam2, Mode::quadtree_entropy}) {
    for (int threads : {1, 2}) {
      ExtractorOptions options = options_for_mode(mode);
      options.threads = threads;
      EXPECT_EQ(allocations_of_third_frame(options, gray), 0)
          << "mode " << to_string(mode) << ", " << threads << " thread(s)";
    }
  }
}

TEST(Allocations, AutomaticThresholdAllocatesNothingEither) {
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  ExtractorOptions options;
  options.auto_threshold = true;
  options.threads = 1;
  EXPECT_EQ(allocations_of_third_frame(options, gray), 0);
}

}  // namespace
}  // namespace aief

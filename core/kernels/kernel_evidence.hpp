#pragma once
// A kernel's evidence, written beside its scalar reference at the end of core/kernels/<kernel>.cpp:
// its validation case (every kernel set gives the reference's bytes) and its benchmark workload.
// Both are registered by the one kernel list (AIEF_FOR_EACH_KERNEL): the declarations and the
// table below are made from it, so a kernel listed without check_<kernel> and
// workload_<kernel> does not link. simd/kernel_validation.cpp runs the checks (the tests and
// `aief validate`), bench/bench_kernel_sets.cpp the workloads.
#include <cstdint>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

// What the benchmark workloads read, filled by bench/bench_kernel_sets.cpp from the graf crop:
// the pyramid the extractor builds (scalar reference), blurred levels, FAST score rows, sample
// keypoints and their descriptors.
struct KernelBenchInputs {
  std::vector<GrayImage> levels, blurred;
  std::vector<ResizePlan> plans;               // plans[n] makes level n from level n - 1
  std::vector<OpenCvResizePlan> opencv_plans;  // the same sizes, for the OpenCV resize
  long long pixels = 0;
  std::vector<std::vector<std::uint8_t>> scores;  // FAST scores (t = 7) of level 0, row by row
  std::vector<PixelPoint> points;                 // a grid over level 0, inside the edge border
  std::vector<float> angles_deg;
  std::vector<std::uint8_t> descriptors;  // of points, 32 bytes each
};

// One kernel's benchmark: `pass` runs it once over its realistic input, and one pass processes
// `items` (pixels, keypoints or descriptor pairs, so rates compare across sizes).
struct KernelWorkload {
  std::function<void()> pass;
  long long items = 0;
};

// "" when `other`'s kernel gives `scalar`'s bytes on `src`, else where it first differs and both
// values (simd/kernel_validation.hpp).
using KernelCheck = std::string (*)(const KernelTable& scalar, const KernelTable& other,
                                    const GrayImage& src);
// The workload of one kernel of `k` over `in` (which outlives it).
using KernelBenchmark = KernelWorkload (*)(const KernelBenchInputs& in, const KernelTable& k);

#define AIEF_DECLARE_KERNEL_EVIDENCE(kernel)                                      \
  std::string check_##kernel(const KernelTable& scalar, const KernelTable& other, \
                             const GrayImage& src);                               \
  KernelWorkload workload_##kernel(const KernelBenchInputs& in, const KernelTable& k);
AIEF_FOR_EACH_KERNEL(AIEF_DECLARE_KERNEL_EVIDENCE)
#undef AIEF_DECLARE_KERNEL_EVIDENCE

struct KernelEvidence {
  const char* kernel;
  KernelCheck check;
  KernelBenchmark workload;
};

// Every kernel's evidence, in table order.
inline const KernelEvidence kKernelEvidence[] = {
#define AIEF_KERNEL_EVIDENCE(kernel) {#kernel, &check_##kernel, &workload_##kernel},
    AIEF_FOR_EACH_KERNEL(AIEF_KERNEL_EVIDENCE)
#undef AIEF_KERNEL_EVIDENCE
};

// What the checks share. "WxH detail": which image a difference is on.
std::string where(const GrayImage& image, const std::string& detail);

// "what [i]: scalar A, SET B" at the first index where two outputs differ (or their sizes), or "".
template <class T>
std::string first_difference(const std::vector<T>& reference, const std::vector<T>& other,
                             const char* set_name, const std::string& what) {
  const std::size_t n = reference.size() < other.size() ? reference.size() : other.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (reference[i] != other[i]) {
      std::ostringstream out;
      out << what << " [" << i << "]: scalar " << +reference[i] << ", " << set_name << " "
          << +other[i];
      return out.str();
    }
  }
  if (reference.size() != other.size())
    return what + ": scalar gives " + std::to_string(reference.size()) + " values, " + set_name +
           " " + std::to_string(other.size());
  return "";
}

// "WxH at (x, y): scalar A, SET B" at the first pixel where two images of one size differ, or "".
std::string first_difference_of_images(const GrayImage& a, const GrayImage& b,
                                       const std::string& set_name);

// The points of a grid of `step` over `src`, at least `border` from every edge.
std::vector<PixelPoint> inner_points(const GrayImage& src, int border, int step);

// An image of each one's size (a workload's outputs).
std::vector<GrayImage> images_of_the_same_sizes(const std::vector<GrayImage>& images);

}  // namespace aief

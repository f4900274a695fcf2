#pragma once
// Shared by the benchmarks: sample images, standard sizes, kernel-set names.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "aief/cv_image_view.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"

namespace aief::bench {

// A named gray image: a bundled sample, or a sample resized to a standard size.
struct NamedImage {
  std::string name;  // e.g. "graf_800x640"
  cv::Mat gray;
};

// Extra images the end-to-end benchmarks also run on, comma-separated paths.
inline constexpr const char* kBenchFramesVariable = "AIEF_BENCH_FRAMES";

// The benchmark images: 640x480, the bundled Oxford samples at their sizes, 1920x1080, and the
// frames AIEF_BENCH_FRAMES names.

const std::vector<NamedImage>& benchmark_images();

const cv::Mat& sample_gray(const std::string& sequence);  // img1 of a bundled sequence

}  // namespace aief::bench

// Per-kernel benchmarks: every kernel set the CPU runs, on the standard images, beside OpenCV's
// kernel for the same job. Names read kernel/variant/image, the kernel named as in the kernel
// list (core/kernels/kernel_table.hpp); fast9_detect is both FAST kernels and the corner walk, the
// job cv::FAST with suppression does. Items are pixels so rates compare across sizes.
#include <benchmark/benchmark.h>

#include <cmath>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/extractor.hpp"
#include "bench/bench_support.hpp"
#include "core/kernels/integral_image.hpp"
#include "core/kernels/resize_bilinear_rows.hpp"
#include "core/level/level_geometry.hpp"
#include "simd/kernels.hpp"
#include "tests/fast9_whole_image.hpp"

namespace aief::bench {
namespace {

// The pyramid of an image as the extractor builds it (scalar reference), for the per-level kernels.
struct Pyramid {
  std::vector<GrayImage> levels;
  std::vector<ResizePlan> plans;  // plans[n] makes level n from level n - 1
  long long pixels = 0;
};

Pyramid make_pyramid(const cv::Mat& gray) {
  Pyramid pyramid;
  const std::vector<LevelGeometry> geometry =
      level_geometry(gray.cols, gray.rows, ExtractorOptions{});
  for (std::size_t n = 0; n < geometry.size(); ++n) {
    GrayImage level(geometry[n].width, geometry[n].height);
    if (n == 0) {
      for (int y = 0; y < gray.rows; ++y)
        std::copy_n(gray.ptr<std::uint8_t>(y), gray.cols, level.data() + y * gray.cols);
      pyramid.plans.emplace_back();
    } else {
      pyramid.plans.push_back(make_resize_plan(geometry[n - 1].width, geometry[n - 1].height,
                                               geometry[n].width, geometry[n].height));
      resize_bilinear_rows_scalar(pyramid.levels.back().view(), pyramid.plans.back(),
                                  level.mutable_view(), 0, level.height());
    }
    pyramid.pixels += static_cast<long long>(level.width()) * level.height();
    pyramid.levels.push_back(std::move(level));
  }
  return pyramid;
}

cv::Mat as_mat(const GrayImage& image) {
  return cv::Mat(image.height(), image.width(), CV_8UC1, const_cast<std::uint8_t*>(image.data()));
}

constexpr const char* kResize = listed_kernel("resize_bilinear_rows");
constexpr const char* kGaussian = listed_kernel("gaussian7_rows");
constexpr const char* kHistogram = listed_kernel("accumulate_histogram");
constexpr const char* kRbrief = listed_kernel("rbrief_describe");
constexpr const char* kBox = listed_kernel("box_describe");

// The two descriptors on the same keypoints: those the default extraction keeps on level 0, with
// their angles; rBRIEF reads the blurred level, the box descriptor the level's integral image
// (each made once, outside the timing: their costs are gaussian7_rows and integral_image).
struct Level0Keypoints {
  GrayImage blurred;
  IntegralImage integral;
  std::vector<PixelPoint> points;
  std::vector<BoxPoint> box_points;
  std::vector<float> angles_deg;
};

std::shared_ptr<const Level0Keypoints> level0_keypoints(const Pyramid& pyramid,
                                                        const cv::Mat& gray) {
  auto in = std::make_shared<Level0Keypoints>();
  const GrayImage& level0 = pyramid.levels[0];
  const Features features =
      Extractor(ExtractorOptions{})
          .extract({gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)});
  for (const Keypoint& kp : features.keypoints) {
    if (kp.octave != 0) continue;
    const PixelPoint p{static_cast<int>(std::lround(kp.x)), static_cast<int>(std::lround(kp.y))};
    if (p.x < kEdgeBorder || p.y < kEdgeBorder || p.x >= level0.width() - kEdgeBorder ||
        p.y >= level0.height() - kEdgeBorder)
      continue;
    in->points.push_back(p);
    in->box_points.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
    in->angles_deg.push_back(kp.angle_deg);
  }
  in->blurred = GrayImage(level0.width(), level0.height());
  gaussian7_rows_scalar(level0.view(), in->blurred.mutable_view(), 0, level0.height(), 0,
                        level0.width());
  in->integral.compute(level0.view());
  return in;
}
constexpr const char* kFast =
    "fast9_detect";  // fast9_scores_row + fast9_local_maxima_bits (tests/fast9_whole_image.hpp)

std::string benchmark_name(const char* kernel, const std::string& variant,
                           const std::string& image) {
  return std::string(kernel) + "/" + variant + "/" + image;
}

// A descriptor kernel's benchmark: one pass of describe(out) over the keypoints an iteration,
// 32 bytes a keypoint; items are the keypoints.
template <class Describe>
void register_describe(const std::string& name, std::shared_ptr<const Level0Keypoints> keypoints,
                       Describe describe) {
  benchmark::RegisterBenchmark(name.c_str(), [keypoints, describe](benchmark::State& state) {
    std::vector<std::uint8_t> out(keypoints->points.size() * 32);
    for (auto _ : state) {
      describe(out.data());
      benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<long long>(keypoints->points.size()));
  });
}

void register_kernel_benchmarks() {
  for (const NamedImage& image : benchmark_images()) {
    const auto pyramid = std::make_shared<Pyramid>(make_pyramid(image.gray));
    const auto keypoints = level0_keypoints(*pyramid, image.gray);
    // The box descriptor's integral image of level 0 beside the blur rBRIEF needs (gaussian7_rows
    // above is the whole pyramid's): scalar, one add per pixel and row.
    benchmark::RegisterBenchmark(benchmark_name("integral_image", "scalar", image.name).c_str(),
                                 [pyramid](benchmark::State& state) {
                                   IntegralImage integral;
                                   for (auto _ : state) {
                                     integral.compute(pyramid->levels[0].view());
                                     benchmark::DoNotOptimize(integral.view().data);
                                   }
                                   state.SetItemsProcessed(state.iterations() *
                                                           pyramid->levels[0].width() *
                                                           pyramid->levels[0].height());
                                 });
    for (KernelSet set : available_kernel_sets()) {
      const KernelTable* kernels = &kernel_table(set);
      const std::string variant = std::string(to_string(set));

      benchmark::RegisterBenchmark(
          benchmark_name(kResize, variant, image.name).c_str(),
          [pyramid, kernels](benchmark::State& state) {
            std::vector<GrayImage> out;
            for (std::size_t n = 0; n < pyramid->levels.size(); ++n)
              out.emplace_back(pyramid->levels[n].width(), pyramid->levels[n].height());
            for (auto _ : state)
              for (std::size_t n = 1; n < pyramid->levels.size(); ++n)
                kernels->resize_bilinear_rows(pyramid->levels[n - 1].view(), pyramid->plans[n],
                                              out[n].mutable_view(), 0, out[n].height());
            state.SetItemsProcessed(
                state.iterations() *
                (pyramid->pixels - pyramid->levels[0].width() * pyramid->levels[0].height()));
          });
      benchmark::RegisterBenchmark(benchmark_name(kGaussian, variant, image.name).c_str(),
                                   [pyramid, kernels](benchmark::State& state) {
                                     std::vector<GrayImage> out;
                                     for (const GrayImage& level : pyramid->levels)
                                       out.emplace_back(level.width(), level.height());
                                     for (auto _ : state)
                                       for (std::size_t n = 0; n < pyramid->levels.size(); ++n)
                                         kernels->gaussian7_rows(
                                             pyramid->levels[n].view(), out[n].mutable_view(), 0,
                                             out[n].height(), 0, out[n].width());
                                     state.SetItemsProcessed(state.iterations() * pyramid->pixels);
                                   });
      benchmark::RegisterBenchmark(benchmark_name(kFast, variant, image.name).c_str(),
                                   [pyramid, kernels](benchmark::State& state) {
                                     std::vector<std::uint8_t> scores;
                                     std::vector<std::uint64_t> maxima_bits;
                                     std::vector<FastCorner> corners;
                                     std::size_t found = 0;
                                     for (auto _ : state)
                                       for (const GrayImage& level : pyramid->levels) {
                                         fast9_whole_image(level.view(), 20, *kernels, scores,
                                                           maxima_bits, corners);
                                         found += corners.size();
                                       }
                                     benchmark::DoNotOptimize(found);
                                     state.SetItemsProcessed(state.iterations() * pyramid->pixels);
                                   });
      // Items are keypoints: rbrief and box per keypoint, same keypoints, same run.
      register_describe(benchmark_name(kRbrief, variant, image.name), keypoints,
                        [keypoints, kernels](std::uint8_t* out) {
                          kernels->rbrief_describe(keypoints->blurred.view(),
                                                   keypoints->points.data(),
                                                   keypoints->angles_deg.data(),
                                                   static_cast<int>(keypoints->points.size()), out);
                        });
      register_describe(benchmark_name(kBox, variant, image.name), keypoints,
                        [keypoints, kernels](std::uint8_t* out) {
                          kernels->box_describe(
                              keypoints->integral.view(), keypoints->box_points.data(),
                              keypoints->angles_deg.data(),
                              static_cast<int>(keypoints->box_points.size()), kBoxLevelScale, out);
                        });
      benchmark::RegisterBenchmark(benchmark_name(kHistogram, variant, image.name).c_str(),
                                   [pyramid, kernels](benchmark::State& state) {
                                     std::uint32_t hist[256];
                                     for (auto _ : state)
                                       for (const GrayImage& level : pyramid->levels) {
                                         std::fill(hist, hist + 256, 0u);
                                         kernels->accumulate_histogram(level.data(), level.width(),
                                                                       level.width(),
                                                                       level.height(), hist);
                                         benchmark::DoNotOptimize(hist);
                                       }
                                     state.SetItemsProcessed(state.iterations() * pyramid->pixels);
                                   });
    }

    // OpenCV's kernels for the same jobs, same levels.
    benchmark::RegisterBenchmark(
        benchmark_name(kResize, "opencv", image.name).c_str(), [pyramid](benchmark::State& state) {
          std::vector<cv::Mat> out(pyramid->levels.size());
          for (auto _ : state)
            for (std::size_t n = 1; n < pyramid->levels.size(); ++n)
              cv::resize(as_mat(pyramid->levels[n - 1]), out[n],
                         cv::Size(pyramid->levels[n].width(), pyramid->levels[n].height()), 0, 0,
                         cv::INTER_LINEAR);
          state.SetItemsProcessed(
              state.iterations() *
              (pyramid->pixels - pyramid->levels[0].width() * pyramid->levels[0].height()));
        });
    benchmark::RegisterBenchmark(benchmark_name(kGaussian, "opencv", image.name).c_str(),
                                 [pyramid](benchmark::State& state) {
                                   std::vector<cv::Mat> out(pyramid->levels.size());
                                   for (auto _ : state)
                                     for (std::size_t n = 0; n < pyramid->levels.size(); ++n)
                                       cv::GaussianBlur(as_mat(pyramid->levels[n]), out[n],
                                                        cv::Size(7, 7), 2, 2,
                                                        cv::BORDER_REFLECT_101);
                                   state.SetItemsProcessed(state.iterations() * pyramid->pixels);
                                 });
    benchmark::RegisterBenchmark(benchmark_name(kFast, "opencv", image.name).c_str(),
                                 [pyramid](benchmark::State& state) {
                                   std::vector<cv::KeyPoint> keypoints;
                                   for (auto _ : state)
                                     for (const GrayImage& level : pyramid->levels)
                                       cv::FAST(as_mat(level), keypoints, 20, true);
                                   state.SetItemsProcessed(state.iterations() * pyramid->pixels);
                                 });
    benchmark::RegisterBenchmark(benchmark_name(kHistogram, "opencv", image.name).c_str(),
                                 [pyramid](benchmark::State& state) {
                                   cv::Mat hist;
                                   const int channels[] = {0};
                                   const int bins[] = {256};
                                   const float range[] = {0, 256};
                                   const float* ranges[] = {range};
                                   for (auto _ : state)
                                     for (const GrayImage& level : pyramid->levels) {
                                       cv::Mat mat = as_mat(level);
                                       cv::calcHist(&mat, 1, channels, cv::Mat(), hist, 1, bins,
                                                    ranges);
                                     }
                                   state.SetItemsProcessed(state.iterations() * pyramid->pixels);
                                 });
  }
}

const bool registered = (register_kernel_benchmarks(), true);

}  // namespace
}  // namespace aief::bench

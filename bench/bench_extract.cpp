// End to end: extract per mode, kernel set and thread count on the standard images, beside
// cv::ORB (1000, 1.2, 8) detectAndCompute on the same gray image.
#include <benchmark/benchmark.h>

#include <opencv2/features2d.hpp>

#include <string>

#include "aief/extractor.hpp"
#include "bench/bench_support.hpp"
#include "simd/kernels.hpp"

namespace aief::bench {
namespace {

// Every row times a frame after one untimed frame (OpenCV's rows too): the steady cost of a
// video's frames, not the first frame's allocation of its buffers, which the page faults make
// several times a frame (quality mode at 1920 x 1080: 97-190 ms first, 18-20 ms after; with few
// iterations a repetition, as there, the first frame decided the median).

// One extraction of `gray` per iteration under `options`.
void register_extract(const std::string& name, const cv::Mat* gray, ExtractorOptions options) {
  benchmark::RegisterBenchmark(name.c_str(), [gray, options](benchmark::State& state) {
    Extractor extractor(options);
    Features features;
    extractor.extract(view_of(*gray), features);  // untimed
    for (auto _ : state) extractor.extract(view_of(*gray), features);
    state.counters["keypoints"] = static_cast<double>(features.keypoints.size());
    state.SetItemsProcessed(state.iterations() * gray->cols * gray->rows);
  })->Unit(benchmark::kMillisecond);
}

void register_extract_benchmarks() {
  for (const NamedImage& image : benchmark_images()) {
    const cv::Mat* gray = &image.gray;
    for (Mode mode :
         {Mode::aief, Mode::orbslam2, Mode::quadtree_entropy, Mode::faithful, Mode::quality}) {
      for (KernelSet set : available_kernel_sets()) {
        for (int threads : {1, 2}) {
          // Other modes: one thread, the best set and AVX2 (the CPUs without AVX-512); the
          // quality mode, scheduled over its 18 levels, two threads on the best set too.
          const bool quality_two_threads =
              mode == Mode::quality && threads == 2 && set == best_kernel_set();
          if (mode != Mode::aief && !quality_two_threads &&
              (threads != 1 || (set != best_kernel_set() && set != KernelSet::avx2)))
            continue;
          const std::string name = "extract/" + std::string(to_string(mode)) + "/" +
                                   std::string(to_string(set)) + "/t" + std::to_string(threads) +
                                   "/" + image.name;
          ExtractorOptions options = options_for_mode(mode);
          options.kernels = set;
          options.threads = threads;
          register_extract(name, gray, options);
        }
      }
    }
    // The entropy-guided variants, each alone on the quadtree modes: one thread, the best
    // set; the mode's own row above is the baseline.
    struct Variant {
      const char* name;
      void (*apply)(ExtractorOptions&);
    };
    static constexpr Variant kVariants[] = {
        {"quadtree-weight-entropy",
         [](ExtractorOptions& o) { o.quadtree_weight = QuadtreeWeight::entropy; }},
        {"fast-threshold-from-entropy",
         [](ExtractorOptions& o) { o.fast_threshold_from = FastThresholdFrom::entropy; }},
        {"low-entropy-sharpen", [](ExtractorOptions& o) { o.low_entropy_sharpen = true; }},
    };
    for (Mode mode : {Mode::orbslam2, Mode::faithful}) {
      for (const Variant& variant : kVariants) {
        ExtractorOptions options = options_for_mode(mode);
        variant.apply(options);
        // The per-block thresholds act on the engine's blocks, not ORB-SLAM's cells: no row.
        if (options.fast_threshold_from == FastThresholdFrom::entropy &&
            options.detection_cells != DetectionCells::blocks)
          continue;
        const std::string name = "extract/" + std::string(to_string(mode)) + "+" + variant.name +
                                 "/" + std::string(to_string(best_kernel_set())) + "/t1/" +
                                 image.name;
        options.kernels = best_kernel_set();
        options.threads = 1;
        register_extract(name, gray, options);
      }
    }
    // The quality mode's parts, each alone on the aief mode: one thread, AVX2 (docs/speed.md).
    static constexpr Variant kQualityParts[] = {
        {"detection-smoothing-1.5", [](ExtractorOptions& o) { o.detection_smoothing = 1.5; }},
        {"pyramid-1.15x10",
         [](ExtractorOptions& o) {
           o.scale_factor = 1.15;
           o.n_levels = 10;
         }},
    };
    for (const Variant& variant : kQualityParts) {
      const std::string name =
          "extract/aief+" + std::string(variant.name) + "/avx2/t1/" + image.name;
      ExtractorOptions options = options_for_mode(Mode::aief);
      variant.apply(options);
      options.kernels = KernelSet::avx2;
      options.threads = 1;
      register_extract(name, gray, options);
    }
    // AKAZE with OpenCV's defaults, detectAndCompute (the quality mode's speed target).
    benchmark::RegisterBenchmark(
        ("extract/opencv_akaze/" + image.name).c_str(),
        [gray](benchmark::State& state) {
          cv::Ptr<cv::AKAZE> akaze = cv::AKAZE::create();
          std::vector<cv::KeyPoint> keypoints;
          cv::Mat descriptors;
          akaze->detectAndCompute(*gray, cv::noArray(), keypoints, descriptors);  // untimed
          for (auto _ : state)
            akaze->detectAndCompute(*gray, cv::noArray(), keypoints, descriptors);
          state.counters["keypoints"] = static_cast<double>(keypoints.size());
          state.SetItemsProcessed(state.iterations() * gray->cols * gray->rows);
        })
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
        ("extract/opencv_orb/" + image.name).c_str(),
        [gray](benchmark::State& state) {
          cv::Ptr<cv::ORB> orb = cv::ORB::create(1000, 1.2f, 8);
          std::vector<cv::KeyPoint> keypoints;
          cv::Mat descriptors;
          orb->detectAndCompute(*gray, cv::noArray(), keypoints, descriptors);  // untimed
          for (auto _ : state) orb->detectAndCompute(*gray, cv::noArray(), keypoints, descriptors);
          state.counters["keypoints"] = static_cast<double>(keypoints.size());
          state.SetItemsProcessed(state.iterations() * gray->cols * gray->rows);
        })
        ->Unit(benchmark::kMillisecond);
  }
}

const bool registered = (register_extract_benchmarks(), true);

}  // namespace
}  // namespace aief::bench

// Every kernel of every kernel set this CPU runs, with no OpenCV: it builds wherever the engine
// does, the aarch64 cross build included (aief_bench_kernel_sets). Names read kernel/set/image;
// items are pixels (keypoints, descriptor pairs) so rates compare. Input: the bundled PGM crop
// of graf, read without OpenCV. bench/kernel_instructions.py counts, under qemu-aarch64, the
// instructions one iteration of each executes (docs/arm.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "aief/extractor.hpp"
#include "core/kernels/kernel_evidence.hpp"
#include "core/level/level_geometry.hpp"
#include "simd/kernels.hpp"
#include "tests/pgm_image.hpp"

namespace aief::bench {
namespace {

using Inputs = KernelBenchInputs;  // core/kernels/kernel_evidence.hpp

std::shared_ptr<const Inputs> make_inputs(const GrayImage& image) {
  auto in = std::make_shared<Inputs>();
  const KernelTable& scalar = kernel_table(KernelSet::scalar);
  const std::vector<LevelGeometry> geometry =
      level_geometry(image.width(), image.height(), ExtractorOptions{});
  for (std::size_t n = 0; n < geometry.size(); ++n) {
    GrayImage level(geometry[n].width, geometry[n].height);
    if (n == 0) {
      level = image;
      in->plans.emplace_back();
      in->opencv_plans.emplace_back();
    } else {
      in->plans.push_back(make_resize_plan(geometry[n - 1].width, geometry[n - 1].height,
                                           geometry[n].width, geometry[n].height));
      in->opencv_plans.push_back(make_opencv_resize_plan(
          geometry[n - 1].width, geometry[n - 1].height, geometry[n].width, geometry[n].height));
      scalar.resize_bilinear_rows(in->levels.back().view(), in->plans.back(), level.mutable_view(),
                                  0, level.height());
    }
    GrayImage blurred(level.width(), level.height());
    scalar.gaussian7_rows(level.view(), blurred.mutable_view(), 0, level.height(), 0,
                          level.width());
    in->pixels += static_cast<long long>(level.width()) * level.height();
    in->levels.push_back(std::move(level));
    in->blurred.push_back(std::move(blurred));
  }
  const GrayImage& level0 = in->levels[0];
  in->scores.assign(static_cast<std::size_t>(level0.height()),
                    std::vector<std::uint8_t>(static_cast<std::size_t>(level0.width()), 0));
  for (int y = 3; y < level0.height() - 3; ++y)
    scalar.fast9_scores_row(level0.view().row(y), level0.width(), 3, level0.width() - 3, 7,
                            in->scores[static_cast<std::size_t>(y)].data());
  for (int y = kEdgeBorder; y < level0.height() - kEdgeBorder; y += 8)
    for (int x = kEdgeBorder; x < level0.width() - kEdgeBorder; x += 8) {
      in->points.push_back({x, y});
      in->angles_deg.push_back(static_cast<float>((x * 7 + y * 13) % 360));
    }
  in->descriptors.resize(in->points.size() * 32);
  scalar.rbrief_describe(in->blurred[0].view(), in->points.data(), in->angles_deg.data(),
                         static_cast<int>(in->points.size()), in->descriptors.data());
  return in;
}

// One kernel's workload (core/kernels/<kernel>.cpp, made from the kernel list).
void bench_kernel(benchmark::State& state, KernelBenchmark workload, const Inputs& in,
                  const KernelTable& k) {
  const KernelWorkload work = workload(in, k);
  for (auto _ : state) work.pass();
  state.SetItemsProcessed(state.iterations() * work.items);
}

// The whole pipeline, one thread.
void bench_extract(benchmark::State& state, const GrayImage& image, KernelSet set) {
  ExtractorOptions options;
  options.kernels = set;
  options.threads = 1;
  Extractor extractor(options);
  Features features;
  for (auto _ : state) {
    extractor.extract(image.view(), features);
    benchmark::DoNotOptimize(features.keypoints.data());
  }
  state.SetItemsProcessed(state.iterations() * image.width() * image.height());
}

}  // namespace

// iterations > 0 fixes every benchmark's iteration count (--aief_iterations=N): two runs that
// differ by one iteration differ by exactly one pass of the kernel, whatever the set-up costs.
void register_kernel_set_benchmarks(int iterations) {
  const GrayImage image =
      test::read_pgm(std::string(AIEF_SAMPLE_DIR) + "/graf/img1_center_320x240.pgm");
  const std::string image_name = "graf_320x240";
  const std::shared_ptr<const Inputs> in = make_inputs(image);
  for (KernelSet set : available_kernel_sets()) {
    const KernelTable* k = &kernel_table(set);
    const auto add = [&](const char* kernel, auto&& body) {
      const std::string name =
          std::string(kernel) + "/" + std::string(to_string(set)) + "/" + image_name;
      benchmark::internal::Benchmark* b = benchmark::RegisterBenchmark(name.c_str(), body);
      if (iterations > 0) b->Iterations(iterations);
    };
    for (const KernelEvidence& kernel : kKernelEvidence)
      add(kernel.kernel, [in, k, workload = kernel.workload](benchmark::State& state) {
        bench_kernel(state, workload, *in, *k);
      });
    add("extract", [image, set](benchmark::State& state) { bench_extract(state, image, set); });
  }
}

}  // namespace aief::bench

int main(int argc, char** argv) {
  int iterations = 0;
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--aief_iterations=", 18) == 0) {
      iterations = std::atoi(argv[i] + 18);
      for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];  // not a Google Benchmark flag
      --argc;
      break;
    }
  try {
    aief::bench::register_kernel_set_benchmarks(iterations);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aief_bench_kernel_sets: error: %s\n", e.what());
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

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
#include "core/kernels/fast9.hpp"
#include "core/level/level_geometry.hpp"
#include "core/kernels/pyramid_resize.hpp"
#include "core/kernels/pyramid_resize_opencv.hpp"
#include "simd/kernels.hpp"
#include "tests/pgm_image.hpp"

namespace aief::bench {
namespace {

// What every kernel reads: the pyramid the extractor builds (scalar reference), blurred levels,
// FAST score rows, sample keypoints and descriptors.
struct Inputs {
  std::vector<GrayImage> levels, blurred;
  std::vector<ResizePlan> plans;               // plans[n] makes level n from level n - 1
  std::vector<OpenCvResizePlan> opencv_plans;  // the same sizes, for the OpenCV resize
  long long pixels = 0;
  std::vector<std::vector<std::uint8_t>> scores;  // FAST scores (t = 7) of level 0, row by row
  std::vector<PixelPoint> points;                 // a grid over level 0, inside the edge border
  std::vector<float> angles_deg;
  std::vector<std::uint8_t> descriptors;  // of points, 32 bytes each
};

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

// One benchmark body per kernel of the list (core/kernels/kernel_table.hpp), each named bench_<kernel>:
// a kernel added to the list without one here does not compile.
void bench_resize_bilinear_rows(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  std::vector<GrayImage> out;
  for (const GrayImage& level : in.levels) out.emplace_back(level.width(), level.height());
  for (auto _ : state)
    for (std::size_t n = 1; n < in.levels.size(); ++n)
      k.resize_bilinear_rows(in.levels[n - 1].view(), in.plans[n], out[n].mutable_view(), 0,
                             out[n].height());
  state.SetItemsProcessed(state.iterations() *
                          (in.pixels - in.levels[0].width() * in.levels[0].height()));
}

void bench_resize_opencv_linear_rows(benchmark::State& state, const Inputs& in,
                                     const KernelTable& k) {
  std::vector<GrayImage> out;
  for (const GrayImage& level : in.levels) out.emplace_back(level.width(), level.height());
  for (auto _ : state)
    for (std::size_t n = 1; n < in.levels.size(); ++n)
      k.resize_opencv_linear_rows(in.levels[n - 1].view(), in.opencv_plans[n],
                                  out[n].mutable_view(), 0, out[n].height());
  state.SetItemsProcessed(state.iterations() *
                          (in.pixels - in.levels[0].width() * in.levels[0].height()));
}

void bench_gaussian7_rows(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  std::vector<GrayImage> out;
  for (const GrayImage& level : in.levels) out.emplace_back(level.width(), level.height());
  for (auto _ : state)
    for (std::size_t n = 0; n < in.levels.size(); ++n)
      k.gaussian7_rows(in.levels[n].view(), out[n].mutable_view(), 0, out[n].height(), 0,
                       out[n].width());
  state.SetItemsProcessed(state.iterations() * in.pixels);
}

void bench_unsharp_row(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  // Every row of every level at amounts across the range (the sharpening of low-entropy blocks).
  std::vector<std::int16_t> amounts(static_cast<std::size_t>(in.levels[0].width()));
  for (std::size_t x = 0; x < amounts.size(); ++x)
    amounts[x] = static_cast<std::int16_t>(x * 7 % (kUnsharpMaxAmountQ8 + 1));
  std::vector<std::uint16_t> sums(amounts.size() + 4);
  std::vector<std::uint8_t> out(amounts.size());
  for (auto _ : state)
    for (const GrayImage& level : in.levels)
      for (int y = 0; y < level.height(); ++y)
        k.unsharp_row(level.view(), y, amounts.data(), sums.data(), out.data());
  benchmark::DoNotOptimize(out.data());
  state.SetItemsProcessed(state.iterations() * in.pixels);
}

void bench_binomial5_row(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  // Every row of every level once (one pass of the detection smoothing).
  std::vector<std::uint16_t> sums(static_cast<std::size_t>(in.levels[0].width()) + 4);
  std::vector<std::uint8_t> out(static_cast<std::size_t>(in.levels[0].width()));
  for (auto _ : state)
    for (const GrayImage& level : in.levels)
      for (int y = 0; y < level.height(); ++y) k.binomial5_row(level.view(), y, sums.data(), out.data());
  benchmark::DoNotOptimize(out.data());
  state.SetItemsProcessed(state.iterations() * in.pixels);
}

void bench_accumulate_histogram(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  std::uint32_t hist[256];
  for (auto _ : state)
    for (const GrayImage& level : in.levels)  // 32 x 32 blocks, as the entropy stage reads them
      for (int y = 0; y + 32 <= level.height(); y += 32)
        for (int x = 0; x + 32 <= level.width(); x += 32) {
          std::fill(hist, hist + 256, 0u);
          k.accumulate_histogram(level.data() + y * level.width() + x, level.width(), 32, 32, hist);
          benchmark::DoNotOptimize(hist);
        }
  state.SetItemsProcessed(state.iterations() * in.pixels);
}

void bench_fast9_scores_row(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  std::vector<std::uint8_t> scores(static_cast<std::size_t>(in.levels[0].width()));
  for (auto _ : state)
    for (const GrayImage& level : in.levels)
      for (int y = 3; y < level.height() - 3; ++y) {
        k.fast9_scores_row(level.view().row(y), level.width(), 3, level.width() - 3, 7,
                           scores.data());
        benchmark::DoNotOptimize(scores.data());
      }
  state.SetItemsProcessed(state.iterations() * in.pixels);
}

void bench_fast9_local_maxima_bits(benchmark::State& state, const Inputs& in,
                                   const KernelTable& k) {
  const int width = static_cast<int>(in.scores[0].size());
  std::vector<std::uint64_t> bits(2 * static_cast<std::size_t>(fast9_maxima_words(width)));
  const int words = fast9_maxima_words(width - 2);
  for (auto _ : state)
    for (std::size_t y = 1; y + 1 < in.scores.size(); ++y) {
      k.fast9_local_maxima_bits(in.scores[y - 1].data(), in.scores[y].data(),
                                in.scores[y + 1].data(), 1, width - 1, 20, bits.data(),
                                bits.data() + words);
      benchmark::DoNotOptimize(bits.data());
    }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<long long>(in.scores.size() * in.scores[0].size()));
}

void bench_ic_moments(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  std::vector<std::int32_t> m10(in.points.size()), m01(in.points.size());
  for (auto _ : state) {
    k.ic_moments(in.levels[0].view(), in.points.data(), static_cast<int>(in.points.size()),
                 m10.data(), m01.data());
    benchmark::DoNotOptimize(m10.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long long>(in.points.size()));
}

void bench_rbrief_describe(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  std::vector<std::uint8_t> descriptors(in.descriptors.size());
  for (auto _ : state) {
    k.rbrief_describe(in.blurred[0].view(), in.points.data(), in.angles_deg.data(),
                      static_cast<int>(in.points.size()), descriptors.data());
    benchmark::DoNotOptimize(descriptors.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long long>(in.points.size()));
}

void bench_hamming_256_many(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  const int n = std::min(static_cast<int>(in.points.size()), 512);
  std::vector<std::uint16_t> distances(static_cast<std::size_t>(n));
  for (auto _ : state)
    for (int i = 0; i < n; ++i) {  // every descriptor against all, as brute-force matching does
      k.hamming_256_many(in.descriptors.data() + 32 * i, in.descriptors.data(), n,
                         distances.data());
      benchmark::DoNotOptimize(distances.data());
    }
  state.SetItemsProcessed(state.iterations() * n * n);
}

// The sweep matcher's layout.
void bench_hamming_256_blocked(benchmark::State& state, const Inputs& in, const KernelTable& k) {
  const int n = std::min(static_cast<int>(in.points.size()), 512);
  std::vector<std::uint32_t> blocked;
  block_descriptors(in.descriptors.data(), n, blocked);
  const int blocks = hamming_block_count(n);
  std::vector<std::uint16_t> distances(static_cast<std::size_t>(blocks * kHammingBlock));
  for (auto _ : state)
    for (int i = 0; i < n; ++i) {
      k.hamming_256_blocked(in.descriptors.data() + 32 * i, blocked.data(), blocks,
                            distances.data());
      benchmark::DoNotOptimize(distances.data());
    }
  state.SetItemsProcessed(state.iterations() * n * n);
}

// The sweep matcher's filter over one query's distances to every train descriptor: the trains
// within the larger of the query's bound and their own, here a bound of 64 bits on both sides.
void bench_positions_within_bounds(benchmark::State& state, const Inputs& in,
                                   const KernelTable& k) {
  const int n = std::min(static_cast<int>(in.points.size()), 512);
  std::vector<std::uint16_t> distances(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    hamming_256_many_scalar(in.descriptors.data() + 32 * i, in.descriptors.data(), n,
                            distances.data() + static_cast<std::ptrdiff_t>(i) * n);
  const std::vector<std::int16_t> train_bounds(static_cast<std::size_t>(n), 64);
  std::vector<std::int32_t> positions(static_cast<std::size_t>(n));
  for (auto _ : state)
    for (int i = 0; i < n; ++i) {
      const int within =
          k.positions_within_bounds(distances.data() + static_cast<std::ptrdiff_t>(i) * n,
                                    train_bounds.data(), n, 64, positions.data());
      benchmark::DoNotOptimize(within);
      benchmark::DoNotOptimize(positions.data());
    }
  state.SetItemsProcessed(state.iterations() * n * n);
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
#define AIEF_KERNEL_BENCHMARK(kernel) \
  add(#kernel, [in, k](benchmark::State& state) { bench_##kernel(state, *in, *k); });
    AIEF_FOR_EACH_KERNEL(AIEF_KERNEL_BENCHMARK)
#undef AIEF_KERNEL_BENCHMARK
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

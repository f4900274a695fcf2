// The adaptive sweep on a pair (all C thresholds) beside what it replaces: one plain extract of
// both images and one match (the bar: the sweep costs at most 3x that). adapt/ratio
// times both alternately in one loop, so its sweep_over_pair counter is a same-run ratio (read
// the median of --benchmark_repetitions on a busy machine).
#include <chrono>

#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>

#include "aief/adapt.hpp"
#include "aief/extractor.hpp"
#include "aief/match.hpp"
#include "bench/bench_support.hpp"

namespace aief::bench {
namespace {

cv::Mat second_image(const std::string& sequence) {
  return cv::imread(std::string(AIEF_SAMPLE_DIR) + "/" + sequence + "/img2.png",
                    cv::IMREAD_GRAYSCALE);
}

void register_adapt_benchmarks() {
  for (const char* sequence : {"graf", "leuven"}) {
    const cv::Mat* a = &sample_gray(sequence);
    const auto b = std::make_shared<cv::Mat>(second_image(sequence));
    for (int threads : {1, 2}) {
      const std::string suffix = "/t" + std::to_string(threads) + "/" + sequence;
      benchmark::RegisterBenchmark(("adapt/sweep" + suffix).c_str(), [a, b, threads](
                                                                         benchmark::State& state) {
        ExtractorOptions options;
        options.threads = threads;
        AdaptiveSweep sweep(options);  // reused, as a user sweeping many pairs would
        AdaptResult result;
        for (auto _ : state) sweep.run(view_of(*a), view_of(*b), result);
        state.counters["thresholds"] = static_cast<double>(result.curve.size());
      })->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(
          ("adapt/extract_both_and_match" + suffix).c_str(),
          [a, b, threads](benchmark::State& state) {
            ExtractorOptions options;
            options.threads = threads;
            Extractor extractor(options);
            Features fa, fb;
            for (auto _ : state) {
              extractor.extract(view_of(*a), fa);
              extractor.extract(view_of(*b), fb);
              benchmark::DoNotOptimize(match_descriptors(fa.descriptors, fb.descriptors));
            }
          })
          ->Unit(benchmark::kMillisecond);
    }
  }
}

// One sweep, then one extract of both images and one match, per iteration.
void register_ratio_benchmarks() {
  for (const char* sequence : {"graf", "leuven", "boat"}) {
    const cv::Mat* a = &sample_gray(sequence);
    const auto b = std::make_shared<cv::Mat>(second_image(sequence));
    for (int threads : {1, 2}) {
      const std::string name = "adapt/ratio/t" + std::to_string(threads) + "/" + sequence;
      benchmark::RegisterBenchmark(name.c_str(), [a, b, threads](benchmark::State& state) {
        using Clock = std::chrono::steady_clock;
        ExtractorOptions options;
        options.threads = threads;
        Extractor extractor(options);
        Features fa, fb;
        AdaptiveSweep sweep(options);
        AdaptResult result;
        sweep.run(view_of(*a), view_of(*b), result);  // warm, as the extractor's first frame
        double sweep_s = 0, pair_s = 0;
        for (auto _ : state) {
          const Clock::time_point start = Clock::now();
          sweep.run(view_of(*a), view_of(*b), result);
          const Clock::time_point swept = Clock::now();
          extractor.extract(view_of(*a), fa);
          extractor.extract(view_of(*b), fb);
          benchmark::DoNotOptimize(match_descriptors(fa.descriptors, fb.descriptors));
          const Clock::time_point paired = Clock::now();
          sweep_s += std::chrono::duration<double>(swept - start).count();
          pair_s += std::chrono::duration<double>(paired - swept).count();
        }
        const double iterations = static_cast<double>(state.iterations());
        state.counters["sweep_ms"] = 1e3 * sweep_s / iterations;
        state.counters["pair_ms"] = 1e3 * pair_s / iterations;
        state.counters["sweep_over_pair"] = pair_s > 0 ? sweep_s / pair_s : 0.0;
      })->Unit(benchmark::kMillisecond);
    }
  }
}

const bool ratio_registered = (register_ratio_benchmarks(), true);
const bool registered = (register_adapt_benchmarks(), true);

}  // namespace
}  // namespace aief::bench

// Extraction on a 2-core board where the SLAM system's own threads want the cores too: how many
// threads should one extractor use? Wall-clock time (what tracking latency sees), 1 vs 2 aief
// threads (and 0, TBB's shared default arena), in the situations ORB-SLAM2/3 create:
//   contended/aief/tT/idle/IMG      nothing else runs (the baseline)
//   contended/aief/tT/busy1/IMG     one other thread of the process spins all the time, as local
//                                   mapping or loop closing do while tracking extracts
//   stereo_pair/aief/tT/IMG         two extractors at once, one per std::thread, as ORB-SLAM's
//                                   stereo Frame extracts the left and right images
// Run with repetitions and read medians (README, "Threads on a 2-core board").
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>

#include "aief/extractor.hpp"
#include "bench/bench_support.hpp"

namespace aief::bench {
namespace {

// A thread that keeps one core busy until destroyed: integer work the compiler cannot drop,
// never sleeping or yielding, as a mapping thread in the middle of bundle adjustment.
class BusyThread {
 public:
  BusyThread() : thread_([this] { spin(); }) {}
  ~BusyThread() {
    stop_.store(true, std::memory_order_relaxed);
    thread_.join();
  }
  BusyThread(const BusyThread&) = delete;
  BusyThread& operator=(const BusyThread&) = delete;

 private:
  void spin() {
    std::uint64_t state = 88172645463325252ULL;
    while (!stop_.load(std::memory_order_relaxed)) {
      for (int i = 0; i < 1024; ++i) state ^= state << 13, state ^= state >> 7, state ^= state << 17;  // xorshift64
      benchmark::DoNotOptimize(state);
    }
  }

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

ExtractorOptions options_with_threads(int threads) {
  ExtractorOptions options;  // AIEF mode, best kernels: what the drop-ins build
  options.threads = threads;
  return options;
}

void register_contended_benchmarks() {
  for (const NamedImage& image : benchmark_images()) {
    if (image.name != "640x480" && image.name != "graf_800x640") continue;  // SLAM camera sizes
    const cv::Mat* gray = &image.gray;
    for (int threads : {0, 1, 2}) {  // 0: TBB's default arena, what the drop-ins use unless told
      for (int busy : {0, 1}) {
        const std::string name = "contended/aief/t" + std::to_string(threads) + (busy ? "/busy1/" : "/idle/") + image.name;
        benchmark::RegisterBenchmark(name.c_str(), [gray, threads, busy](benchmark::State& state) {
          Extractor extractor(options_with_threads(threads));
          Features features;
          extractor.extract(view_of(*gray), features);  // buffers sized before the competitor starts
          std::vector<std::unique_ptr<BusyThread>> competitors;
          for (int i = 0; i < busy; ++i) competitors.push_back(std::make_unique<BusyThread>());
          for (auto _ : state) extractor.extract(view_of(*gray), features);
          state.SetItemsProcessed(state.iterations() * gray->cols * gray->rows);
        })->Unit(benchmark::kMillisecond)->UseRealTime();
      }
      const std::string name = "stereo_pair/aief/t" + std::to_string(threads) + "/" + image.name;
      benchmark::RegisterBenchmark(name.c_str(), [gray, threads](benchmark::State& state) {
        Extractor left(options_with_threads(threads)), right(options_with_threads(threads));
        Features left_features, right_features;
        left.extract(view_of(*gray), left_features);
        right.extract(view_of(*gray), right_features);
        for (auto _ : state) {
          // A thread per image and frame, as ORB-SLAM's Frame constructor starts them.
          std::thread left_thread([&] { left.extract(view_of(*gray), left_features); });
          std::thread right_thread([&] { right.extract(view_of(*gray), right_features); });
          left_thread.join();
          right_thread.join();
        }
        state.SetItemsProcessed(state.iterations() * 2 * gray->cols * gray->rows);
      })->Unit(benchmark::kMillisecond)->UseRealTime();
    }
  }
}

const bool registered = (register_contended_benchmarks(), true);

}  // namespace
}  // namespace aief::bench

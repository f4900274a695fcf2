// Extraction on a 2-core board where the SLAM system's own threads want the cores too: how many
// threads should one extractor use? 1 vs 2 aief threads (and 0, TBB's shared default arena, what
// the drop-ins use unless told), in the situations ORB-SLAM2/3 create:
//   idle    one extractor, nothing else running (the baseline)
//   busy1   one extractor while another thread of the process spins all the time, as local
//           mapping or loop closing do while tracking extracts
//   stereo  two extractors at once, each on its own camera thread, as ORB-SLAM's stereo Frame
//           extracts the left and right images (the frame is done when both are)
//   stereo_busy1  the stereo pair while another thread spins: a stereo rig during mapping
// Benchmarks:
//   contended/aief/tT/SITUATION/IMG      wall-clock time per frame (what tracking latency sees);
//                                        CPU is the whole process's (every thread, a busy
//                                        competitor's included), so with no competitor CPU over
//                                        real time is how many cores the frame kept busy
//   threads_ratio/aief/t2_vs_t1/SITUATION/IMG
//                                        1 and 2 threads alternately in one loop: counters
//                                        t1_ms, t2_ms (medians over the iterations) and
//                                        t2_over_t1 (median of the per-frame ratios), which
//                                        holds up when other processes load the machine unevenly
// The camera threads live across frames: ORB-SLAM starts two std::threads per frame, which costs
// a few tens of microseconds on a quiet board, but on a shared machine a newly started thread
// gets a small CPU share at first and would measure the machine, not the extractor.
// Run with repetitions and read medians (docs/speed.md, "Threads on a 2-core board").
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
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
      for (int i = 0; i < 1024; ++i)
        state ^= state << 13, state ^= state >> 7, state ^= state << 17;  // xorshift64
      benchmark::DoNotOptimize(state);
    }
  }

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// The cameras of a rig, each with its own extractor. One camera extracts in the calling thread
// (ORB-SLAM's tracking thread); two extract at once on two camera threads, and extract_frame
// returns when both are done.
class Rig {
 public:
  Rig(int cameras, int threads_per_extractor, const cv::Mat& gray) : gray_(gray) {
    ExtractorOptions options;  // AIEF mode, best kernels: what the drop-ins build
    options.threads = threads_per_extractor;
    for (int i = 0; i < cameras; ++i) cameras_.push_back(std::make_unique<Camera>(options));
    for (auto& camera : cameras_) camera->extract(gray_);  // buffers sized before timing
    if (cameras > 1)
      for (std::size_t i = 0; i < cameras_.size(); ++i)
        threads_.emplace_back([this, i] { camera_loop(i); });
  }
  ~Rig() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    frame_started_.notify_all();
    for (std::thread& thread : threads_) thread.join();
  }
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  void extract_frame() {
    if (threads_.empty()) {
      cameras_[0]->extract(gray_);
      return;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    ++frame_;
    running_ = threads_.size();
    frame_started_.notify_all();
    frame_done_.wait(lock, [this] { return running_ == 0; });
  }

 private:
  struct Camera {
    explicit Camera(const ExtractorOptions& options) : extractor(options) {}
    void extract(const cv::Mat& gray) { extractor.extract(view_of(gray), features); }
    Extractor extractor;
    Features features;
  };

  void camera_loop(std::size_t index) {
    std::uint64_t frames_seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      frame_started_.wait(lock, [&] { return stopping_ || frame_ != frames_seen; });
      if (stopping_) return;
      frames_seen = frame_;
      lock.unlock();
      cameras_[index]->extract(gray_);
      lock.lock();
      if (--running_ == 0) frame_done_.notify_one();
    }
  }

  const cv::Mat& gray_;
  std::vector<std::unique_ptr<Camera>> cameras_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable frame_started_, frame_done_;
  std::uint64_t frame_ = 0;
  std::size_t running_ = 0;
  bool stopping_ = false;
};

enum class Situation { idle, busy1, stereo, stereo_busy1 };

const char* name_of(Situation situation) {
  switch (situation) {
    case Situation::idle: return "idle";
    case Situation::busy1: return "busy1";
    case Situation::stereo: return "stereo";
    case Situation::stereo_busy1: return "stereo_busy1";
  }
  return "?";
}

int cameras_in(Situation situation) {
  return situation == Situation::stereo || situation == Situation::stereo_busy1 ? 2 : 1;
}

std::unique_ptr<BusyThread> competitor_for(Situation situation) {
  const bool busy = situation == Situation::busy1 || situation == Situation::stereo_busy1;
  return busy ? std::make_unique<BusyThread>() : nullptr;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double frame_milliseconds(Rig& rig) {
  const auto start = std::chrono::steady_clock::now();
  rig.extract_frame();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

void register_contended_benchmarks() {
  for (const NamedImage& image : benchmark_images()) {
    if (image.name != "640x480" && image.name != "graf_800x640") continue;  // SLAM camera sizes
    const cv::Mat* gray = &image.gray;
    for (Situation situation :
         {Situation::idle, Situation::busy1, Situation::stereo, Situation::stereo_busy1}) {
      for (int threads : {0, 1, 2}) {
        const std::string name = "contended/aief/t" + std::to_string(threads) + "/" +
                                 name_of(situation) + "/" + image.name;
        benchmark::RegisterBenchmark(
            name.c_str(),
            [gray, threads, situation](benchmark::State& state) {
              Rig rig(cameras_in(situation), threads, *gray);
              const std::unique_ptr<BusyThread> competitor = competitor_for(situation);
              for (auto _ : state) rig.extract_frame();
              state.SetItemsProcessed(state.iterations() * cameras_in(situation) * gray->cols *
                                      gray->rows);
            })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MeasureProcessCPUTime();
      }
      const std::string name =
          "threads_ratio/aief/t2_vs_t1/" + std::string(name_of(situation)) + "/" + image.name;
      benchmark::RegisterBenchmark(
          name.c_str(),
          [gray, situation](benchmark::State& state) {
            Rig one_thread(cameras_in(situation), 1, *gray),
                two_threads(cameras_in(situation), 2, *gray);
            const std::unique_ptr<BusyThread> competitor = competitor_for(situation);
            std::vector<double> t1, t2, ratio;
            bool two_first = false;
            for (auto _ : state) {
              // Alternate which runs first, so neither always follows the other.
              const double first = frame_milliseconds(two_first ? two_threads : one_thread);
              const double second = frame_milliseconds(two_first ? one_thread : two_threads);
              t1.push_back(two_first ? second : first);
              t2.push_back(two_first ? first : second);
              ratio.push_back(t2.back() / t1.back());
              two_first = !two_first;
            }
            state.counters["t1_ms"] = median(t1);
            state.counters["t2_ms"] = median(t2);
            state.counters["t2_over_t1"] = median(ratio);
          })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

const bool registered = (register_contended_benchmarks(), true);

}  // namespace
}  // namespace aief::bench

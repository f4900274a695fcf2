#pragma once
// Fair times on a shared machine: the methods are timed in rounds, each round running every
// method once in an order rotated by one from the last (a method is never always first, after the
// slowest, or in the same phase of a load burst), and each method's time is the median of its
// rounds with the fastest and slowest beside it. Both the process's CPU time (what the work
// costs; waits for a busy core are not in it) and the wall-clock time are kept, and the machine's
// load average is recorded with them.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <ctime>
#include <fstream>
#include <functional>
#include <vector>

namespace aief::eval {

struct TimeSpread {
  double median_ms = 0, min_ms = 0, max_ms = 0;
  int runs = 0;
};

// The method run at position `slot` of round `round`, among `methods`.
inline std::size_t interleaved_method(std::size_t methods, std::size_t round, std::size_t slot) {
  return (round + slot) % methods;
}

inline TimeSpread spread_of(std::vector<double> times_ms) {
  TimeSpread t;
  if (times_ms.empty()) return t;
  std::sort(times_ms.begin(), times_ms.end());
  const std::size_t n = times_ms.size();
  t.median_ms = n % 2 ? times_ms[n / 2] : (times_ms[n / 2 - 1] + times_ms[n / 2]) / 2;
  t.min_ms = times_ms.front();
  t.max_ms = times_ms.back();
  t.runs = static_cast<int>(n);
  return t;
}

struct MethodTimes {
  TimeSpread cpu, wall;
};

// `rounds` rounds over `work` (one callable per method), interleaved as above.
inline std::vector<MethodTimes> time_interleaved(const std::vector<std::function<void()>>& work,
                                                 int rounds) {
  using Clock = std::chrono::steady_clock;
  std::vector<std::vector<double>> cpu(work.size()), wall(work.size());
  for (int round = 0; round < rounds; ++round)
    for (std::size_t slot = 0; slot < work.size(); ++slot) {
      const std::size_t m = interleaved_method(work.size(), static_cast<std::size_t>(round), slot);
      const std::clock_t cpu_start = std::clock();  // the whole process: worker threads count too
      const auto wall_start = Clock::now();
      work[m]();
      wall[m].push_back(
          std::chrono::duration<double, std::milli>(Clock::now() - wall_start).count());
      cpu[m].push_back(1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    }
  std::vector<MethodTimes> out;
  for (std::size_t m = 0; m < work.size(); ++m)
    out.push_back({spread_of(std::move(cpu[m])), spread_of(std::move(wall[m]))});
  return out;
}

// The machine's 1-minute load average (/proc/loadavg), the lowest and highest seen while timing;
// negative where it cannot be read.
struct MachineLoad {
  double lowest = -1, highest = -1;
  void sample() {
    double one_minute = -1;
    std::ifstream("/proc/loadavg") >> one_minute;
    if (one_minute < 0) return;
    lowest = lowest < 0 ? one_minute : std::min(lowest, one_minute);
    highest = std::max(highest, one_minute);
  }
};

}  // namespace aief::eval

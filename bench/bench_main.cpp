#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

int main(int argc, char** argv) {
  // OpenCV's baselines run single-threaded, like ours at --threads 1: a second thread does not
  // speed up cv::ORB (docs/speed.md, "Threads on a 2-core board") and ratios stay per core.
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

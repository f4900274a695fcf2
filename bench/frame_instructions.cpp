// Per-frame cost of one extractor run over a sequence, for bench/frame_instructions.py (the video
// benchmark): under valgrind --tool=callgrind --collect-atstart=no, each frame's extract() (the
// carried F's sweep step included) is collected and dumped on its own, reading the images is not;
// outside valgrind the client requests do nothing and the printed wall-clock times are the
// measurement. The frames are read before the first extract(), so no frame waits for a decoder.
//
// usage: aief_frame_instructions [KEY=VALUE...] THRESHOLD FRAME...
//        THRESHOLD: a number, auto, carried, or none (the mode's: orbslam2 has no F); KEY=VALUE:
//        any option of the option table by its record key (distribution=quadtree, mode=orbslam2,
//        kernels=avx2, ...). Threads are 1 unless given, so a count is one thread's work.
// Prints one line a frame: the path, the F it requested, its keypoints and its microseconds.
#include <chrono>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include <valgrind/callgrind.h>

#include "aief/extractor.hpp"
#include "core/options/option_table.hpp"
#include "io/image_io.hpp"

int main(int argc, char** argv) try {
  namespace table = aief::option_table;
  std::vector<table::GivenOption> given;
  bool threads_given = false;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string_view argument = argv[i];
    const std::size_t equals = argument.find('=');
    if (equals == std::string_view::npos) break;
    const std::string key(argument.substr(0, equals));
    given.push_back({&table::row(key), std::string(argument.substr(equals + 1)), key});
    threads_given = threads_given || key == "threads";
  }
  if (argc - i < 2) {
    std::cerr << "usage: aief_frame_instructions [KEY=VALUE...] THRESHOLD FRAME...\n";
    return 2;
  }
  if (std::string_view(argv[i]) != "none")
    given.push_back({&table::row("entropy_threshold"), argv[i], "THRESHOLD"});
  ++i;
  if (!threads_given) given.push_back({&table::row("threads"), "1", "threads"});
  aief::Extractor extractor(table::resolve_options(given));

  std::vector<aief::GrayImage> frames;
  for (int f = i; f < argc; ++f) frames.push_back(aief::io::read_gray_image(argv[f]));
  aief::Features features;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const char* path = argv[i + static_cast<int>(f)];
    CALLGRIND_TOGGLE_COLLECT;
    const auto start = std::chrono::steady_clock::now();
    extractor.extract(frames[f].view(), features);
    const auto stop = std::chrono::steady_clock::now();
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_DUMP_STATS_AT(path);
    std::cout << path << " F=" << features.info.entropy_threshold_requested
              << " keypoints=" << features.keypoints.size()
              << " us=" << std::chrono::duration<double, std::micro>(stop - start).count() << "\n";
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "aief_frame_instructions: " << e.what() << "\n";
  return 1;
}

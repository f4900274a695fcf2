// Instructions per frame of one extractor run over a sequence, for bench/frame_instructions.py:
// under valgrind --tool=callgrind --collect-atstart=no, each frame's extract() (the carried F's
// sweep step included) is collected and dumped on its own, reading the images is not.
// Outside valgrind the client requests do nothing.
//
// usage: aief_frame_instructions THRESHOLD FRAME... (THRESHOLD: a number, auto or carried; the
//        other options are the defaults, with 1 thread so the count is one thread's work)
#include <iostream>
#include <string>
#include <vector>

#include <valgrind/callgrind.h>

#include "aief/extractor.hpp"
#include "core/option_table.hpp"
#include "io/image_io.hpp"

int main(int argc, char** argv) try {
  if (argc < 3) {
    std::cerr << "usage: aief_frame_instructions THRESHOLD FRAME...\n";
    return 2;
  }
  const aief::option_table::OptionRow& threshold = aief::option_table::row("entropy_threshold");
  const aief::option_table::OptionRow& threads = aief::option_table::row("threads");
  aief::Extractor extractor(aief::option_table::resolve_options(
      {{&threshold, argv[1], "THRESHOLD"}, {&threads, "1", "threads"}}));
  aief::Features features;
  for (int i = 2; i < argc; ++i) {
    const aief::GrayImage image = aief::io::read_gray_image(argv[i]);
    CALLGRIND_TOGGLE_COLLECT;
    extractor.extract(image.view(), features);
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_DUMP_STATS_AT(argv[i]);
    std::cout << argv[i] << " F=" << features.info.entropy_threshold_requested
              << " keypoints=" << features.keypoints.size() << "\n";
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "aief_frame_instructions: " << e.what() << "\n";
  return 1;
}

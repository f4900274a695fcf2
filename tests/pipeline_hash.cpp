// aief_pipeline_hash IMAGE.pgm [KERNELS]: the whole pipeline on one PGM under each mode, at 1 and
// 2 threads, with the given kernel set (default auto), one line per run: keypoint count and the
// hash of every output byte (tests/features_hash.hpp). Needs no OpenCV, so
// scripts/ci_aarch64 runs it under qemu-aarch64 and compares its lines with the x86 build's:
// equal lines mean byte-identical output. The kernel set goes to stderr, so stdout is the same
// for every set.
#include <cstdio>
#include <exception>
#include <string>

#include "aief/extractor.hpp"
#include "simd/kernels.hpp"
#include "tests/features_hash.hpp"
#include "tests/pgm_image.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr,
                 "usage: aief_pipeline_hash IMAGE.pgm [auto|scalar|sse4.2|avx2|avx512|neon64]\n");
    return 2;
  }
  try {
    const aief::GrayImage image = aief::test::read_pgm(argv[1]);
    const aief::KernelSet set = aief::parse_kernel_set(argc == 3 ? argv[2] : "auto");
    std::fprintf(stderr, "kernels: %s\n", aief::kernel_table(set).name);
    for (aief::Mode mode :
         {aief::Mode::aief, aief::Mode::aief_paper, aief::Mode::orbslam2,
          aief::Mode::quadtree_entropy, aief::Mode::faithful, aief::Mode::quality}) {
      for (int threads : {1, 2}) {
        aief::ExtractorOptions options = aief::options_for_mode(mode);
        options.kernels = set;
        options.threads = threads;
        const aief::Features features = aief::Extractor(options).extract(image.view());
        std::printf("%s, %d thread(s): %zu keypoints, hash %016llx\n",
                    std::string(aief::to_string(mode)).c_str(), threads, features.keypoints.size(),
                    static_cast<unsigned long long>(aief::test::features_hash(features)));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aief_pipeline_hash: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

// aief_pipeline_hash IMAGE.pgm [KERNELS]: the whole pipeline on one PGM under each mode, at 1 and
// 2 threads, with the given kernel set (default auto), one line per run: keypoint count and a
// 64-bit FNV-1a hash of every keypoint field, descriptor and entropy figure. Needs no OpenCV, so
// scripts/ci_aarch64 runs it under qemu-aarch64 and compares its lines with the x86 build's:
// equal lines mean byte-identical output (floats are hashed bit for bit; both targets are
// little-endian IEEE-754). The kernel set goes to stderr, so stdout is the same for every set.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "aief/extractor.hpp"
#include "simd/kernels.hpp"
#include "tests/pgm_image.hpp"

namespace {

struct Fnv1a64 {
  std::uint64_t state = 0xcbf29ce484222325ull;
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) state = (state ^ bytes[i]) * 0x100000001b3ull;
  }
  template <class T>
  void add_value(const T& value) {
    add(&value, sizeof value);
  }
};

std::uint64_t features_hash(const aief::Features& features) {
  Fnv1a64 hash;
  for (const aief::Keypoint& k : features.keypoints) {  // field by field: no padding bytes hashed
    hash.add_value(k.x);
    hash.add_value(k.y);
    hash.add_value(k.size);
    hash.add_value(k.angle_deg);
    hash.add_value(k.response);
    hash.add_value(k.octave);
  }
  for (const aief::Descriptor& d : features.descriptors) hash.add(d.data(), d.size());
  hash.add_value(features.info.entropy_threshold_used);
  hash.add_value(features.info.image_entropy_bits);
  hash.add_value(features.info.blocks_kept);
  return hash.state;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: aief_pipeline_hash IMAGE.pgm [auto|scalar|sse4.2|avx2|avx512|neon64]\n");
    return 2;
  }
  try {
    const aief::GrayImage image = aief::test::read_pgm(argv[1]);
    const aief::KernelSet set = aief::parse_kernel_set(argc == 3 ? argv[2] : "auto");
    std::fprintf(stderr, "kernels: %s\n", aief::kernel_table(set).name);
    for (aief::Mode mode : {aief::Mode::aief, aief::Mode::orbslam2, aief::Mode::quadtree_entropy}) {
      for (int threads : {1, 2}) {
        aief::ExtractorOptions options = aief::options_for_mode(mode);
        options.kernels = set;
        options.threads = threads;
        const aief::Features features = aief::Extractor(options).extract(image.view());
        std::printf("%s, %d thread(s): %zu keypoints, hash %016llx\n", std::string(aief::to_string(mode)).c_str(), threads,
                    features.keypoints.size(), static_cast<unsigned long long>(features_hash(features)));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aief_pipeline_hash: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

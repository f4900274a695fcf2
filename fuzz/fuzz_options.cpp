// libFuzzer: arbitrary bytes as ExtractorOptions (NaN, infinities, negative, huge, invalid enum
// values) -> Extractor -> extract on a small textured image. Only aief::Error may escape.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "aief/error.hpp"
#include "aief/extractor.hpp"

namespace {

struct Reader {
  const std::uint8_t* data;
  std::size_t size;
  template <class T>
  T take() {
    T value{};
    const std::size_t n = size < sizeof(T) ? size : sizeof(T);
    std::memcpy(&value, data, n);
    data += n;
    size -= n;
    return value;
  }
};

const std::vector<std::uint8_t>& test_image() {
  static const std::vector<std::uint8_t> pixels = [] {
    std::vector<std::uint8_t> p(97 * 83);
    std::uint32_t state = 12345;
    for (std::size_t i = 0; i < p.size(); ++i) {
      state = state * 1664525u + 1013904223u;
      const int x = static_cast<int>(i % 97), y = static_cast<int>(i / 97);
      p[i] = static_cast<std::uint8_t>(((x / 6 + y / 6) % 2) * 160 + (state >> 27));
    }
    return p;
  }();
  return pixels;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in{data, size};
  aief::ExtractorOptions options;
  // Small counts most of the time (fast runs), any value sometimes.
  options.n_features = in.take<std::int32_t>() % 5000;
  options.scale_factor = in.take<double>();
  options.n_levels = in.take<std::int8_t>();
  options.fast_threshold = in.take<std::int16_t>();
  options.fast_min_threshold = in.take<std::int16_t>();
  options.block_size = in.take<std::int16_t>();
  options.entropy_threshold = in.take<double>();
  options.auto_threshold = (in.take<std::uint8_t>() & 1) != 0;
  options.distribution = static_cast<aief::Distribution>(in.take<std::uint8_t>() % 4);
  options.entropy = static_cast<aief::EntropyMeasure>(in.take<std::uint8_t>() % 4);
  options.threads = in.take<std::uint8_t>() % 3;
  options.kernels = static_cast<aief::KernelSet>(in.take<std::uint8_t>() % 6);
  options.candidate_ranking = static_cast<aief::CandidateRanking>(in.take<std::uint8_t>() % 3);
  options.auto_requires_two_classes = (in.take<std::uint8_t>() & 1) != 0;
  try {
    aief::Extractor extractor(options);
    const aief::Features features = extractor.extract({test_image().data(), 97, 83, 97});
    if (static_cast<int>(features.keypoints.size()) > options.n_features) std::abort();
  } catch (const aief::Error&) {
  }
  return 0;
}

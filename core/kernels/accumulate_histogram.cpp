#include "core/kernels/accumulate_histogram.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

void accumulate_histogram_scalar(const std::uint8_t* data, std::ptrdiff_t stride, int width,
                                 int height, std::uint32_t* hist) {
  // Four sub-histograms: consecutive equal pixels would otherwise wait on each other's
  // increment (store-to-load forwarding chain).
  std::uint32_t banks[4][256];
  std::memset(banks, 0, sizeof banks);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = data + y * stride;
    int x = 0;
    for (; x + 4 <= width; x += 4) {
      ++banks[0][row[x]];
      ++banks[1][row[x + 1]];
      ++banks[2][row[x + 2]];
      ++banks[3][row[x + 3]];
    }
    for (; x < width; ++x) ++banks[0][row[x]];
  }
  for (int k = 0; k < 256; ++k) hist[k] += banks[0][k] + banks[1][k] + banks[2][k] + banks[3][k];
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_accumulate_histogram(const KernelTable& scalar, const KernelTable& other,
                                       const GrayImage& src) {
  // The whole image and an inner rectangle with the full stride.
  for (int inset : {0, 1}) {
    const int w = src.width() - 2 * inset, h = src.height() - 2 * inset;
    if (w <= 0 || h <= 0) continue;
    std::vector<std::uint32_t> a(256, 3), b(256, 3);  // accumulate: start from the same counts
    const std::uint8_t* data = src.data() + inset * src.width() + inset;
    scalar.accumulate_histogram(data, src.width(), w, h, a.data());
    other.accumulate_histogram(data, src.width(), w, h, b.data());
    const std::string diff = first_difference(a, b, other.name, "bin");
    if (!diff.empty()) return where(src, "inset " + std::to_string(inset) + " " + diff);
  }
  return "";
}

// 32 x 32 blocks of every level, as the entropy stage reads them.
KernelWorkload workload_accumulate_histogram(const KernelBenchInputs& in, const KernelTable& k) {
  return {[&in, &k] {
            std::uint32_t hist[256];
            for (const GrayImage& level : in.levels)
              for (int y = 0; y + 32 <= level.height(); y += 32)
                for (int x = 0; x + 32 <= level.width(); x += 32) {
                  std::fill(hist, hist + 256, 0u);
                  k.accumulate_histogram(level.data() + y * level.width() + x, level.width(), 32,
                                         32, hist);
                }
          },
          in.pixels};
}

}  // namespace aief

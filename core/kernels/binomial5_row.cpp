#include "core/kernels/binomial5_row.hpp"

#include <algorithm>
#include <cassert>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

std::uint16_t* binomial5_column_sums(ImageView src, int y, std::uint16_t* column_sums) {
  const int width = src.width, last_row = src.height - 1;
  const std::uint8_t* r0 = src.row(std::max(y - 2, 0));
  const std::uint8_t* r1 = src.row(std::max(y - 1, 0));
  const std::uint8_t* r2 = src.row(y);
  const std::uint8_t* r3 = src.row(std::min(y + 1, last_row));
  const std::uint8_t* r4 = src.row(std::min(y + 2, last_row));
  // v holds the column sums of x = -2 .. width + 1, the outer two on each side replicated.
  std::uint16_t* v = column_sums + 2;
  for (int x = 0; x < width; ++x)
    v[x] = static_cast<std::uint16_t>(r0[x] + 4 * r1[x] + 6 * r2[x] + 4 * r3[x] + r4[x]);
  v[-2] = v[-1] = v[0];
  v[width] = v[width + 1] = v[width - 1];
  return v;
}

void binomial5_row_scalar(ImageView src, int y, std::uint16_t* column_sums, std::uint8_t* dst) {
  assert(!src.empty() && y >= 0 && y < src.height);
  const int width = src.width;
  const std::uint16_t* v = binomial5_column_sums(src, y, column_sums);
  for (int x = 0; x < width; ++x) {
    const std::uint32_t blur = v[x - 2] + 4u * v[x - 1] + 6u * v[x] + 4u * v[x + 1] + v[x + 2];
    dst[x] = static_cast<std::uint8_t>((blur + 128) >> 8);
  }
}

std::string check_binomial5_row(const KernelTable& scalar, const KernelTable& other,
                                const GrayImage& src) {
  const std::size_t width = static_cast<std::size_t>(src.width());
  std::vector<std::uint16_t> sums_a(width + 4), sums_b(width + 4);
  std::vector<std::uint8_t> a(width), b(width);
  for (int y = 0; y < src.height(); ++y) {
    scalar.binomial5_row(src.view(), y, sums_a.data(), a.data());
    other.binomial5_row(src.view(), y, sums_b.data(), b.data());
    const std::string diff = first_difference(a, b, other.name, "pixel");
    if (!diff.empty()) return where(src, "row " + std::to_string(y) + " " + diff);
  }
  return "";
}

// Every row of every level once: one pass of the detection smoothing.
KernelWorkload workload_binomial5_row(const KernelBenchInputs& in, const KernelTable& k) {
  const std::size_t width = static_cast<std::size_t>(in.levels[0].width());
  return {[&in, &k, sums = std::vector<std::uint16_t>(width + 4),
           out = std::vector<std::uint8_t>(width)]() mutable {
            for (const GrayImage& level : in.levels)
              for (int y = 0; y < level.height(); ++y)
                k.binomial5_row(level.view(), y, sums.data(), out.data());
          },
          in.pixels};
}

}  // namespace aief

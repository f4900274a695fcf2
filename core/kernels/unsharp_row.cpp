#include "core/kernels/unsharp_row.hpp"

#include "core/kernels/binomial5_row.hpp"

#include <algorithm>
#include <cassert>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

void unsharp_row_scalar(ImageView src, int y, const std::int16_t* amount_q8,
                        std::uint16_t* column_sums, std::uint8_t* dst) {
  assert(!src.empty() && y >= 0 && y < src.height);
  const int width = src.width;
  const std::uint8_t* r2 = src.row(y);
  const std::uint16_t* v = binomial5_column_sums(src, y, column_sums);
  for (int x = 0; x < width; ++x) {
    const std::int32_t blur = v[x - 2] + 4 * v[x - 1] + 6 * v[x] + 4 * v[x + 1] + v[x + 2];
    const std::int32_t detail = 256 * r2[x] - blur;
    // floor((a d + 2^15) / 2^16) with a non-negative dividend: + 2^26, then - 2^10 after the shift.
    const std::int32_t added = ((amount_q8[x] * detail + (1 << 15) + (1 << 26)) >> 16) - (1 << 10);
    dst[x] = static_cast<std::uint8_t>(std::clamp(r2[x] + added, 0, 255));
  }
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_unsharp_row(const KernelTable& scalar, const KernelTable& other,
                              const GrayImage& src) {
  // Amounts over the whole range, 0 and the largest included, from a seed of the image's size.
  std::mt19937 rng(static_cast<std::uint32_t>(src.width() * 131 + src.height()));
  std::uniform_int_distribution<int> amount(0, kUnsharpMaxAmountQ8);
  const std::size_t width = static_cast<std::size_t>(src.width());
  std::vector<std::int16_t> amounts(width);
  std::vector<std::uint16_t> sums_a(width + 4), sums_b(width + 4);
  std::vector<std::uint8_t> a(width), b(width);
  for (int y = 0; y < src.height(); ++y) {
    for (std::int16_t& value : amounts) value = static_cast<std::int16_t>(amount(rng));
    amounts[0] = kUnsharpMaxAmountQ8;
    amounts[width - 1] = 0;
    scalar.unsharp_row(src.view(), y, amounts.data(), sums_a.data(), a.data());
    other.unsharp_row(src.view(), y, amounts.data(), sums_b.data(), b.data());
    const std::string diff = first_difference(a, b, other.name, "pixel");
    if (!diff.empty()) return where(src, "row " + std::to_string(y) + " " + diff);
  }
  return "";
}

// Every row of every level at amounts across the range (the sharpening of low-entropy blocks).
KernelWorkload workload_unsharp_row(const KernelBenchInputs& in, const KernelTable& k) {
  std::vector<std::int16_t> amounts(static_cast<std::size_t>(in.levels[0].width()));
  for (std::size_t x = 0; x < amounts.size(); ++x)
    amounts[x] = static_cast<std::int16_t>(x * 7 % (kUnsharpMaxAmountQ8 + 1));
  const std::size_t width = amounts.size();
  return {[&in, &k, amounts = std::move(amounts), sums = std::vector<std::uint16_t>(width + 4),
           out = std::vector<std::uint8_t>(width)]() mutable {
            for (const GrayImage& level : in.levels)
              for (int y = 0; y < level.height(); ++y)
                k.unsharp_row(level.view(), y, amounts.data(), sums.data(), out.data());
          },
          in.pixels};
}

}  // namespace aief

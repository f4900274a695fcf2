#include "core/kernels/integral_image_row.hpp"

#include <cassert>
#include <memory>
#include <string>
#include <vector>

#include "core/kernels/integral_image.hpp"
#include "core/kernels/kernel_evidence.hpp"

namespace aief {

void integral_image_row_scalar(const std::uint8_t* pixels, int width, const std::uint32_t* above,
                               std::uint32_t* out) {
  assert(width >= 1);
  out[0] = 0;
  integral_image_row_from(pixels, 0, 0, width, above, out);
}

// The whole integral image of `src` row by row, and once more above a row of large entries
// (near 2^32, so the sums wrap as they do deep in a large image).
std::string check_integral_image_row(const KernelTable& scalar, const KernelTable& other,
                                     const GrayImage& src) {
  const int width = src.width();
  const std::size_t entries = static_cast<std::size_t>(width) + 1;
  std::vector<std::uint32_t> above_a(entries, 0), above_b(entries, 0), a(entries), b(entries);
  std::vector<std::uint32_t> high(entries);
  for (std::size_t x = 0; x < entries; ++x)
    high[x] = 0xFFFFFF00u + static_cast<std::uint32_t>(x * 2654435761u % 509u);
  for (int y = 0; y < src.height(); ++y) {
    scalar.integral_image_row(src.view().row(y), width, above_a.data(), a.data());
    other.integral_image_row(src.view().row(y), width, above_b.data(), b.data());
    std::string diff = first_difference(a, b, other.name, "entry");
    if (!diff.empty()) return where(src, "row " + std::to_string(y) + " " + diff);
    scalar.integral_image_row(src.view().row(y), width, high.data(), a.data());
    other.integral_image_row(src.view().row(y), width, high.data(), b.data());
    diff = first_difference(a, b, other.name, "entry");
    if (!diff.empty()) return where(src, "row " + std::to_string(y) + " above 2^32 - 256 " + diff);
    above_a.swap(a);
    above_b.swap(b);
  }
  return "";
}

// The integral image of every level (what a frame with the box descriptor makes).
KernelWorkload workload_integral_image_row(const KernelBenchInputs& in, const KernelTable& k) {
  auto integrals = std::make_shared<std::vector<IntegralImage>>(in.levels.size());
  return {[&in, &k, integrals]() {
            for (std::size_t n = 0; n < in.levels.size(); ++n)
              (*integrals)[n].compute(in.levels[n].view(), k);
          },
          in.pixels};
}

}  // namespace aief

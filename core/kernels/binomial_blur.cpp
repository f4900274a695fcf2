#include "core/kernels/binomial_blur.hpp"

#include <algorithm>
#include <cassert>

namespace aief {

void binomial5_row_scalar(ImageView src, int y, std::uint16_t* column_sums, std::uint8_t* dst) {
  assert(!src.empty() && y >= 0 && y < src.height);
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
  for (int x = 0; x < width; ++x) {
    const std::uint32_t blur = v[x - 2] + 4u * v[x - 1] + 6u * v[x] + 4u * v[x + 1] + v[x + 2];
    dst[x] = static_cast<std::uint8_t>((blur + 128) >> 8);
  }
}

}  // namespace aief

#include "core/kernels/gaussian_blur.hpp"

#include <cassert>
#include <vector>

namespace aief {

namespace {

int reflect101(int i, int size) {
  if (i < 0) return -i;
  if (i >= size) return 2 * size - 2 - i;
  return i;
}

// Horizontal pass of columns [x_begin, x_end) of one source row into h (u16 per pixel).
void horizontal(const std::uint8_t* row, int width, int x_begin, int x_end, std::uint16_t* h) {
  const auto& k = kGaussian7Q8;
  for (int x = x_begin; x < x_end; ++x) {
    std::uint32_t sum = 0;
    if (x >= 3 && x + 3 < width) {
      for (int t = 0; t < 7; ++t) sum += k[static_cast<std::size_t>(t)] * row[x + t - 3];
    } else {
      for (int t = 0; t < 7; ++t)
        sum += k[static_cast<std::size_t>(t)] * row[reflect101(x + t - 3, width)];
    }
    h[x] = static_cast<std::uint16_t>(sum);
  }
}

}  // namespace

void gaussian7_rows_scalar(ImageView src, MutableImageView dst, int y_begin, int y_end, int x_begin,
                           int x_end) {
  assert(src.width >= 4 && src.height >= 4);
  assert(0 <= x_begin && x_begin <= x_end && x_end <= src.width);
  const int width = src.width, height = src.height;
  // Seven horizontal rows in a ring, refilled as the window slides down.
  thread_local std::vector<std::uint16_t> ring;
  ring.resize(static_cast<std::size_t>(7) * static_cast<std::size_t>(width));
  constexpr int kNoRow = -1000000;  // rows above the image (-1 .. -3) are legitimate keys
  int ring_row[7] = {kNoRow, kNoRow, kNoRow, kNoRow, kNoRow, kNoRow, kNoRow};
  const auto horizontal_row = [&](int sy) -> const std::uint16_t* {
    const int slot = ((sy % 7) + 7) % 7;
    std::uint16_t* h =
        ring.data() + static_cast<std::size_t>(slot) * static_cast<std::size_t>(width);
    if (ring_row[slot] != sy) {
      horizontal(src.row(reflect101(sy, height)), width, x_begin, x_end, h);
      ring_row[slot] = sy;
    }
    return h;
  };
  const auto& k = kGaussian7Q8;
  for (int y = y_begin; y < y_end; ++y) {
    const std::uint16_t* rows[7];
    for (int t = 0; t < 7; ++t) rows[t] = horizontal_row(y + t - 3);
    std::uint8_t* out = dst.row(y - y_begin);
    for (int x = x_begin; x < x_end; ++x) {
      std::uint32_t sum = 32768;
      for (int t = 0; t < 7; ++t)
        sum += k[static_cast<std::size_t>(t)] * static_cast<std::uint32_t>(rows[t][x]);
      out[x] = static_cast<std::uint8_t>(sum >> 16);
    }
  }
}

}  // namespace aief

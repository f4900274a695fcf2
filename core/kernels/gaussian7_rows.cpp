#include "core/kernels/gaussian7_rows.hpp"

#include <algorithm>
#include <cassert>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

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

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_gaussian7_rows(const KernelTable& scalar, const KernelTable& other,
                                 const GrayImage& src) {
  if (src.width() < 4 || src.height() < 4) return "";
  GrayImage a(src.width(), src.height()), b(src.width(), src.height());
  scalar.gaussian7_rows(src.view(), a.mutable_view(), 0, src.height(), 0, src.width());
  // The other kernel in two bands, as the extractor streams it (dst row 0 is the band's first
  // row), and each band in column spans, as it blurs only the columns rBRIEF reads: a span at
  // either edge, a narrow one (scalar tail) and a wide one.
  const int cut = src.height() / 3;
  std::vector<int> column_cuts = {0, std::min(src.width(), 5), src.width() / 2, src.width()};
  column_cuts.erase(std::unique(column_cuts.begin(), column_cuts.end()), column_cuts.end());
  for (std::size_t i = 0; i + 1 < column_cuts.size(); ++i) {
    other.gaussian7_rows(src.view(), b.mutable_view(), 0, cut, column_cuts[i], column_cuts[i + 1]);
    other.gaussian7_rows(
        src.view(), {b.data() + cut * src.width(), src.width(), src.height() - cut, src.width()},
        cut, src.height(), column_cuts[i], column_cuts[i + 1]);
  }
  return first_difference_of_images(a, b, other.name);
}

// Every level of the pyramid, whole.
KernelWorkload workload_gaussian7_rows(const KernelBenchInputs& in, const KernelTable& k) {
  return {[&in, &k, out = images_of_the_same_sizes(in.levels)]() mutable {
            for (std::size_t n = 0; n < in.levels.size(); ++n)
              k.gaussian7_rows(in.levels[n].view(), out[n].mutable_view(), 0, out[n].height(), 0,
                               out[n].width());
          },
          in.pixels};
}

}  // namespace aief

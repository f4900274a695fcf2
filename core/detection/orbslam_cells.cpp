#include "core/detection/orbslam_cells.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

#include "core/kernels/fast9_scores_row.hpp"

namespace aief {

namespace {

struct CellAxis {
  int count = 0;  // nCols / nRows
  int side = 0;   // wCell / hCell
};

// ORB-SLAM's float arithmetic: nCols = width / W (truncated), wCell = ceil(width / nCols).
CellAxis cell_axis(int size) {
  const float extent = static_cast<float>(size - 2 * kOrbSlamMinBorder);
  CellAxis axis;
  axis.count = static_cast<int>(extent / kOrbSlamCellSide);
  if (axis.count > 0) axis.side = static_cast<int>(std::ceil(extent / axis.count));
  return axis;
}

}  // namespace

void detect_orbslam_cells(ImageView pixels, const ExtractorOptions& options,
                          const KernelTable& kernels, OrbSlamCellScratch& scratch,
                          std::vector<Candidate>& out) {
  const int width = pixels.width, height = pixels.height;
  const CellAxis cols = cell_axis(width), rows = cell_axis(height);
  if (cols.count <= 0 || rows.count <= 0) return;
  const int max_border_x = width - kOrbSlamMinBorder, max_border_y = height - kOrbSlamMinBorder;

  // The level's scores at fast_min_threshold (0 below it) over every pixel a cell scores: cell
  // images lie in [16, size - 16), and cv::FAST scores 3 pixels in from their edges. Then their
  // local maxima as bit rows (bit i of a row is x = x_begin + i), read by every cell.
  const int x_begin = kOrbSlamMinBorder + 3, x_end = max_border_x - 3;
  const int y_begin = kOrbSlamMinBorder + 3, y_end = max_border_y - 3;
  if (x_end <= x_begin || y_end <= y_begin) return;
  // Only the one-pixel frame around the scored area is read besides it (the maxima kernel's
  // ring): zero that, not the level.
  const auto w = static_cast<std::size_t>(width);
  std::vector<std::uint8_t>& scores = scratch.scores;
  scores.resize(w * static_cast<std::size_t>(height));
  for (const int y : {y_begin - 1, y_end})
    std::fill_n(scores.data() + y * w + (x_begin - 1), x_end - x_begin + 2, std::uint8_t{0});
  for (int y = y_begin; y < y_end; ++y) {
    std::uint8_t* row = scores.data() + y * w;
    row[x_begin - 1] = row[x_end] = 0;
    kernels.fast9_scores_row(pixels.row(y), pixels.stride, x_begin, x_end,
                             options.fast_min_threshold, row);
  }
  const int words = fast9_maxima_words(x_end - x_begin);
  const auto bit_row = [&](std::vector<std::uint64_t>& bits, int y) {
    return bits.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(words);
  };
  const auto bit_rows = static_cast<std::size_t>(words) * static_cast<std::size_t>(height);
  scratch.maxima.resize(bit_rows);
  scratch.strong.resize(bit_rows);
  for (int y = y_begin; y < y_end; ++y) {
    const std::uint8_t* row = scores.data() + y * w;
    kernels.fast9_local_maxima_bits(row - w, row, row + w, x_begin, x_end, options.fast_threshold,
                                    bit_row(scratch.maxima, y), bit_row(scratch.strong, y));
  }
  // The first and last row of a cell row's scored areas have no neighbours above (below) inside
  // their cells: their maxima against a zero row there, two bit rows a cell row (ring_* [2i] the
  // first row, [2i + 1] the last).
  const auto cell_rows_of = [&](int i) {  // the scored rows [sy0, sy1) of cell row i
    const int y0 = kOrbSlamMinBorder + i * rows.side;
    const int y1 = std::min(y0 + rows.side + 6, max_border_y);
    return std::pair<int, int>{y0 + 3, y1 - 3};
  };
  scratch.zero_row.assign(w, 0);
  const auto ring_rows = static_cast<std::size_t>(2 * rows.count) * static_cast<std::size_t>(words);
  scratch.ring_maxima.resize(ring_rows);
  scratch.ring_strong.resize(ring_rows);
  for (int i = 0; i < rows.count; ++i) {
    const auto [sy0, sy1] = cell_rows_of(i);
    if (sy1 <= sy0) continue;
    const std::uint8_t* zero = scratch.zero_row.data();
    for (int last = 0; last < 2; ++last) {
      const int y = last ? sy1 - 1 : sy0;
      const std::uint8_t* row = scores.data() + y * w;
      kernels.fast9_local_maxima_bits(y == sy0 ? zero : row - w, row, y == sy1 - 1 ? zero : row + w,
                                      x_begin, x_end, options.fast_threshold,
                                      bit_row(scratch.ring_maxima, 2 * i + last),
                                      bit_row(scratch.ring_strong, 2 * i + last));
    }
  }

  // cv::FAST with suppression on the cell image of cell row i [x0, x1) x [y0, y1) at threshold
  // t: scored area [sx0, sx1) x [sy0, sy1), 3 pixels in from its edges, neighbours outside it
  // count 0. Row by row: the first and last column one by one, the columns between from bits.
  const auto fast_in_cell = [&](int i, int x0, int x1, int t) {
    const std::size_t first = out.size();
    const int sx0 = x0 + 3, sx1 = x1 - 3;
    // Named copies, not structured bindings: a lambda may not capture those before C++20
    // (clang 14, the sanitizer job's compiler, refuses it).
    const std::pair<int, int> scored = cell_rows_of(i);
    const int sy0 = scored.first, sy1 = scored.second;
    if (sx1 <= sx0 || sy1 <= sy0) return false;
    const auto inside = [&](int nx, int ny) -> int {
      return nx >= sx0 && nx < sx1 && ny >= sy0 && ny < sy1 ? scores[ny * w + nx] : 0;
    };
    // A pixel of the first or last column with s >= t, where some neighbours lie outside and
    // count 0.
    const auto edge_pixel = [&](int x, int y) {
      const int s = scores[y * w + x];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if ((dx != 0 || dy != 0) && inside(x + dx, y + dy) >= s) return;
      out.push_back(Candidate{x, y, s, static_cast<std::uint8_t>(inside(x - 1, y)),
                              static_cast<std::uint8_t>(inside(x + 1, y)),
                              static_cast<std::uint8_t>(inside(x, y - 1)),
                              static_cast<std::uint8_t>(inside(x, y + 1)), 0});
    };
    // The columns between, [sx0 + 1, sx1 - 1), as bits: words k_first .. k_last of a bit row.
    const bool strong = t == options.fast_threshold;
    const int first_bit = sx0 + 1 - x_begin, end_bit = sx1 - 1 - x_begin;
    const bool any_between = end_bit > first_bit;
    const int k_first = first_bit / 64, k_last = any_between ? (end_bit - 1) / 64 : k_first;
    const std::uint64_t first_mask = ~std::uint64_t{0} << (first_bit % 64);
    const std::uint64_t last_mask =
        end_bit % 64 != 0 ? ~(~std::uint64_t{0} << (end_bit % 64)) : ~std::uint64_t{0};
    const std::uint64_t* inner_bits = (strong ? scratch.strong : scratch.maxima).data();
    const std::uint64_t* ring_bits =
        bit_row(strong ? scratch.ring_strong : scratch.ring_maxima, 2 * i);
    for (int y = sy0; y < sy1; ++y) {
      const std::uint8_t* row = scores.data() + y * w;
      if (row[sx0] >= t) edge_pixel(sx0, y);
      if (any_between) {
        const bool top = y == sy0, bottom = y == sy1 - 1;
        const std::uint64_t* row_bits = top      ? ring_bits
                                        : bottom ? ring_bits + words
                                                 : inner_bits + static_cast<std::size_t>(y) * words;
        for (int k = k_first; k <= k_last; ++k) {
          std::uint64_t word = row_bits[k];
          if (k == k_first) word &= first_mask;
          if (k == k_last) word &= last_mask;
          for (; word != 0; word &= word - 1) {
            const int x = x_begin + 64 * k + std::countr_zero(word);
            out.push_back(Candidate{x, y, row[x], row[x - 1], row[x + 1],
                                    top ? std::uint8_t{0} : row[x - width],
                                    bottom ? std::uint8_t{0} : row[x + width], 0});
          }
        }
      }
      if (sx1 - 1 > sx0 && row[sx1 - 1] >= t) edge_pixel(sx1 - 1, y);
    }
    return out.size() > first;
  };

  for (int i = 0; i < rows.count; ++i) {
    const int y0 = kOrbSlamMinBorder + i * rows.side;
    if (y0 >= max_border_y - 3) continue;
    for (int j = 0; j < cols.count; ++j) {
      const int x0 = kOrbSlamMinBorder + j * cols.side;
      if (x0 >= max_border_x - 6) continue;
      const int x1 = std::min(x0 + cols.side + 6, max_border_x);
      if (!fast_in_cell(i, x0, x1, options.fast_threshold))
        fast_in_cell(i, x0, x1, options.fast_min_threshold);
    }
  }
}

}  // namespace aief

#include "core/orbslam_cells.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/fast9.hpp"

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
                          const KernelTable& kernels, std::vector<std::uint8_t>& scores,
                          std::vector<Candidate>& out) {
  const int width = pixels.width, height = pixels.height;
  const CellAxis cols = cell_axis(width), rows = cell_axis(height);
  if (cols.count <= 0 || rows.count <= 0) return;
  const int max_border_x = width - kOrbSlamMinBorder, max_border_y = height - kOrbSlamMinBorder;

  // The level's scores at fast_min_threshold (0 below it) over every pixel a cell scores: cell
  // images lie in [16, size - 16), and cv::FAST scores 3 pixels in from their edges.
  const int x_begin = kOrbSlamMinBorder + 3, x_end = max_border_x - 3;
  const int y_begin = kOrbSlamMinBorder + 3, y_end = max_border_y - 3;
  if (x_end <= x_begin || y_end <= y_begin) return;
  scores.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  for (int y = y_begin; y < y_end; ++y)
    kernels.fast9_scores_row(pixels.row(y), pixels.stride, x_begin, x_end,
                             options.fast_min_threshold, scores.data() + y * width);
  const auto score = [&](int x, int y) { return scores[static_cast<std::size_t>(y) * width + x]; };

  // cv::FAST with suppression on the cell image [x0, x1) x [y0, y1) at threshold t: scored area
  // 3 pixels in from its edges, neighbours outside it count 0.
  const auto fast_in_cell = [&](int x0, int x1, int y0, int y1, int t) {
    const std::size_t first = out.size();
    const int sx0 = x0 + 3, sx1 = x1 - 3, sy0 = y0 + 3, sy1 = y1 - 3;
    for (int y = sy0; y < sy1; ++y) {
      const std::uint8_t* row = scores.data() + static_cast<std::size_t>(y) * width;
      for (int x = sx0; x < sx1; ++x) {
        // Corners at fast_min_threshold are sparse: skip eight non-corners at a time.
        std::uint64_t eight = 0;
        if (x + 8 <= sx1) std::memcpy(&eight, row + x, 8);
        if (x + 8 <= sx1 && eight == 0) {
          x += 7;
          continue;
        }
        const int s = row[x];
        if (s < t) continue;
        bool peak = true;
        for (int dy = -1; dy <= 1 && peak; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            const int nx = x + dx, ny = y + dy;
            if (nx < sx0 || nx >= sx1 || ny < sy0 || ny >= sy1) continue;  // counts 0
            const int n = score(nx, ny);
            if (n >= t && s <= n) {
              peak = false;
              break;
            }
          }
        if (!peak) continue;
        Candidate c;
        c.x = x;
        c.y = y;
        c.score = s;
        const auto inside = [&](int nx, int ny) {
          return nx >= sx0 && nx < sx1 && ny >= sy0 && ny < sy1 ? score(nx, ny) : 0;
        };
        c.score_left = static_cast<std::uint8_t>(inside(x - 1, y));
        c.score_right = static_cast<std::uint8_t>(inside(x + 1, y));
        c.score_up = static_cast<std::uint8_t>(inside(x, y - 1));
        c.score_down = static_cast<std::uint8_t>(inside(x, y + 1));
        out.push_back(c);
      }
    }
    return out.size() > first;
  };

  for (int i = 0; i < rows.count; ++i) {
    const int y0 = kOrbSlamMinBorder + i * rows.side;
    if (y0 >= max_border_y - 3) continue;
    const int y1 = std::min(y0 + rows.side + 6, max_border_y);
    for (int j = 0; j < cols.count; ++j) {
      const int x0 = kOrbSlamMinBorder + j * cols.side;
      if (x0 >= max_border_x - 6) continue;
      const int x1 = std::min(x0 + cols.side + 6, max_border_x);
      if (!fast_in_cell(x0, x1, y0, y1, options.fast_threshold))
        fast_in_cell(x0, x1, y0, y1, options.fast_min_threshold);
    }
  }
}

}  // namespace aief

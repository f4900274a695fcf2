#include "core/level/caller_mask.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

namespace aief {

void binarise_mask_rows(ImageView mask, MutableImageView level_mask, int y_begin, int y_end) {
  for (int y = y_begin; y < y_end; ++y) {
    const std::uint8_t* in = mask.row(y);
    std::uint8_t* out = level_mask.row(y);
    for (int x = 0; x < mask.width; ++x) out[x] = in[x] != 0 ? 255 : 0;
  }
}

void clear_partial_mask_rows(MutableImageView level_mask, int y_begin, int y_end) {
  for (int y = y_begin; y < y_end; ++y) {
    std::uint8_t* row = level_mask.row(y);
    for (int x = 0; x < level_mask.width; ++x) row[x] = row[x] == 255 ? 255 : 0;
  }
}

void blocks_allowed(ImageView level_mask, const BlockGrid& grid,
                    std::vector<std::uint8_t>& allowed) {
  allowed.assign(static_cast<std::size_t>(grid.count()), 0);
  for (int r = 0; r < grid.rows(); ++r)
    for (int c = 0; c < grid.cols(); ++c) {
      const int x0 = grid.col_edges[static_cast<std::size_t>(c)],
                x1 = grid.col_edges[static_cast<std::size_t>(c) + 1];
      bool any = false;
      for (int y = grid.row_edges[static_cast<std::size_t>(r)];
           y < grid.row_edges[static_cast<std::size_t>(r) + 1] && !any; ++y) {
        const std::uint8_t* row = level_mask.row(y);
        any = std::any_of(row + x0, row + x1, [](std::uint8_t v) { return v != 0; });
      }
      allowed[static_cast<std::size_t>(r * grid.cols() + c)] = any ? 1 : 0;
    }
}

void allowed_bits(const std::uint8_t* row, int x_begin, int x_end, std::uint64_t* words) {
  const int count = x_end - x_begin;
  for (int k = 0; k * 64 < count; ++k) {
    std::uint64_t word = 0;
    const int end = std::min(64, count - 64 * k);
    const std::uint8_t* pixels = row + x_begin + 64 * k;
    for (int i = 0; i < end; ++i) word |= static_cast<std::uint64_t>(pixels[i] != 0) << i;
    words[k] = word;
  }
}

}  // namespace aief

#include "core/level/level_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace aief {

namespace {

std::vector<int> block_edges(int begin, int end, int block_size) {
  const int length = end - begin;
  // round(length / block_size) blocks, at least one: the last one is between half and one and a
  // half blocks long.
  const int count = std::max(1, (length + block_size / 2) / block_size);
  std::vector<int> edges(static_cast<std::size_t>(count) + 1);
  for (int i = 0; i < count; ++i) edges[static_cast<std::size_t>(i)] = begin + i * block_size;
  edges.back() = end;
  return edges;
}

}  // namespace

BlockGrid make_block_grid(int width, int height, int block_size) {
  BlockGrid grid;
  if (!level_is_usable(width, height)) return grid;
  grid.col_edges = block_edges(kEdgeBorder, width - kEdgeBorder, block_size);
  grid.row_edges = block_edges(kEdgeBorder, height - kEdgeBorder, block_size);
  return grid;
}

namespace {

// Each level's scale and size, `visit(n, scale, width, height)`, exactly as ORB-SLAM2's
// ORBextractor: float products, cvRound of the sizes.
template <class Visit>
void for_each_level_size(int width, int height, const ExtractorOptions& options, Visit&& visit) {
  const float scale_factor = static_cast<float>(options.scale_factor);
  float scale = 1.0f;
  for (int n = 0; n < options.n_levels; ++n) {
    if (n > 0) scale *= scale_factor;
    const float inverse = 1.0f / scale;
    visit(n, scale, static_cast<int>(std::lrint(static_cast<float>(width) * inverse)),
          static_cast<int>(std::lrint(static_cast<float>(height) * inverse)));
  }
}

}  // namespace

long long pyramid_pixels(int width, int height, const ExtractorOptions& options) {
  long long pixels = 0;
  for_each_level_size(width, height, options, [&](int, float, int level_width, int level_height) {
    if (level_is_usable(level_width, level_height))
      pixels += static_cast<long long>(level_width) * level_height;
  });
  return pixels;
}

std::vector<LevelGeometry> level_geometry(int width, int height, const ExtractorOptions& options) {
  const int levels = options.n_levels;
  std::vector<LevelGeometry> geometry(static_cast<std::size_t>(levels));
  for_each_level_size(width, height, options, [&](int n, float scale, int w, int h) {
    LevelGeometry& level = geometry[static_cast<std::size_t>(n)];
    level.scale = scale;
    level.width = w;
    level.height = h;
  });

  // Only the usable levels share the budget (levels shrink, so they are the first ones): a level
  // too small for a keypoint would otherwise keep its share and the frame deliver fewer than N
  // (964 of 1000 with 20 levels). With every level usable, L is n_levels: ORB-SLAM2's budgets.
  int budget_levels = 0;
  while (budget_levels < levels &&
         level_is_usable(geometry[static_cast<std::size_t>(budget_levels)].width,
                         geometry[static_cast<std::size_t>(budget_levels)].height))
    ++budget_levels;
  budget_levels = std::max(budget_levels, 1);

  // Features per level (Eq. 12-17 and ORB-SLAM2): N (1 - s) s^n / (1 - s^L), rounded, with
  // whatever is left on the last level.
  const float factor = 1.0f / static_cast<float>(options.scale_factor);
  float per_scale = static_cast<float>(options.n_features) * (1.0f - factor) /
                    (1.0f - static_cast<float>(std::pow(static_cast<double>(factor),
                                                        static_cast<double>(budget_levels))));
  int assigned = 0;
  for (int n = 0; n < budget_levels - 1; ++n) {
    const int count = static_cast<int>(std::lrint(per_scale));
    geometry[static_cast<std::size_t>(n)].n_features = count;
    assigned += count;
    per_scale *= factor;
  }
  geometry[static_cast<std::size_t>(budget_levels) - 1].n_features =
      std::max(options.n_features - assigned, 0);
  // With many levels and few features the rounding can hand out more than N (17 features over
  // 20 levels at 1.04 round to 1 each; ORB-SLAM2 then returns 19): take the excess back from the
  // smallest levels, so the total never exceeds N.
  for (int n = budget_levels - 1; n >= 0 && assigned > options.n_features; --n) {
    const int take =
        std::min(geometry[static_cast<std::size_t>(n)].n_features, assigned - options.n_features);
    geometry[static_cast<std::size_t>(n)].n_features -= take;
    assigned -= take;
  }

  bool usable = true;
  for (LevelGeometry& level : geometry) {
    usable = usable && level_is_usable(level.width, level.height);
    if (usable) level.grid = make_block_grid(level.width, level.height, options.block_size);
  }
  return geometry;
}

}  // namespace aief

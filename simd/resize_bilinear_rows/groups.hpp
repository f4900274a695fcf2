#pragma once
// What the x86 and the NEON form of resize_bilinear_rows share: the plan's x groups unpacked
// (ResizePlan::x_group_*, core/kernels/resize_bilinear_rows.hpp) and the walk over the rows, each
// row's groups by the family's code and the outputs after the last group by the scalar reference.
#include <cstddef>
#include <cstdint>

#include "core/kernels/resize_bilinear_rows.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

// Group g's 16 source bytes start at start[g]; half h's 16 shuffle bytes are at
// shuffle[h] + 16 g, its 8 int16 weights at weight[h] + 8 g.
struct ResizeGroups {
  int count;
  const std::int32_t* start;
  const std::uint8_t* shuffle[2];
  const std::int16_t* weight[2];

  explicit ResizeGroups(const ResizePlan& plan)
      : count(plan.x_groups),
        start(plan.x_group_start.data()),
        shuffle{plan.x_group_shuffle.data(), plan.x_group_shuffle.data() + 16 * plan.x_groups},
        weight{plan.x_group_weight.data(), plan.x_group_weight.data() + 8 * plan.x_groups} {}
};

// dst rows [y_begin, y_end): groups_of_row(groups, top, bottom, wy, out) writes a row's outputs
// [0, 8 * plan.x_groups) from the plan's groups, its two source rows and the Q8 weight wy of the
// bottom one.
template <class GroupsOfRow>
inline void resize_rows_by_groups(ImageView src, const ResizePlan& plan, MutableImageView dst,
                                  int y_begin, int y_end, const GroupsOfRow& groups_of_row) {
  const ResizeGroups groups(plan);
  for (int y = y_begin; y < y_end; ++y) {
    const int sy = plan.y_index[static_cast<std::size_t>(y)];
    const std::uint32_t wy = plan.y_weight[static_cast<std::size_t>(y)];
    const std::uint8_t* top = src.row(sy);
    const std::uint8_t* bottom = src.row(sy + 1);
    std::uint8_t* out = dst.row(y);
    groups_of_row(groups, top, bottom, wy, out);
    resize_bilinear_span_scalar(top, bottom, plan, wy, 8 * plan.x_groups, plan.dst_width, out);
  }
}

AIEF_SIMD_NAMESPACE_END

#pragma once
// Fixed-point bilinear downsampling, one pyramid level from the previous one (DESIGN.md section 1).
//
// Geometry is cv::resize's INTER_LINEAR: destination pixel x samples the source at
// fx = (x + 0.5) * src_w / dst_w - 0.5, clamped to the image. Weights are Q8 (0..256):
//   wx = round((fx - floor(fx)) * 256), left source index sx = floor(fx)  (wx == 256 -> sx+1, 0)
//   h(y) = src[y][sx] * (256 - wx) + src[y][sx + 1] * wx            <= 65280, fits uint16
//   dst  = (h(sy) * (256 - wy) + h(sy + 1) * wy + 32768) >> 16       integer, exact in any ISA
// The plan clamps indices so that sx + 1 < src_w and sy + 1 < src_h (a weight of 0 on the
// right/bottom tap at the edges). Requires src_w >= 2 and src_h >= 2.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"

namespace aief {

struct ResizePlan {
  int src_width = 0, src_height = 0, dst_width = 0, dst_height = 0;
  std::vector<std::int32_t> x_index;   // dst_width entries: left tap sx, sx + 1 < src_width
  std::vector<std::uint16_t> x_weight; // dst_width entries: Q8 weight of the right tap
  std::vector<std::int32_t> y_index;   // dst_height entries: top tap sy, sy + 1 < src_height
  std::vector<std::uint16_t> y_weight; // dst_height entries: Q8 weight of the bottom tap
};

ResizePlan make_resize_plan(int src_width, int src_height, int dst_width, int dst_height);

// Writes dst rows [y_begin, y_end). dst is plan.dst_width x plan.dst_height, src the plan's
// source size. Reads only src rows y_index[y], y_index[y] + 1 of those rows.
void resize_bilinear_rows_scalar(ImageView src, const ResizePlan& plan, MutableImageView dst,
                                 int y_begin, int y_end);

}  // namespace aief

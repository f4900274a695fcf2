#pragma once
// Fixed-point bilinear downsampling, one pyramid level from the previous one (docs/design.md §2).
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
  std::vector<std::int32_t> x_index;    // dst_width entries: left tap sx, sx + 1 < src_width
  std::vector<std::uint16_t> x_weight;  // dst_width entries: Q8 weight of the right tap
  std::vector<std::int32_t> y_index;    // dst_height entries: top tap sy, sy + 1 < src_height
  std::vector<std::uint16_t> y_weight;  // dst_height entries: Q8 weight of the bottom tap

  // The x taps again, in the form the vector kernel (simd/resize_bilinear_rows/x86.hpp) consumes,
  // for the outputs [0, 8 * x_groups): group g = outputs 8g .. 8g + 7, whose taps all lie in the 16
  // source bytes from x_group_start[g]. Half h (0: outputs 8g .. 8g + 3, 1: 8g + 4 .. 8g + 7) of
  // group g has 16 bytes at x_group_shuffle[(h * x_groups + g) * 16], a pshufb mask putting the
  // left and right tap of each output into the low bytes of two u16 lanes (sx - start, 0x80,
  // sx + 1 - start, 0x80), and 8 int16 at x_group_weight[(h * x_groups + g) * 8], the matching
  // pmaddwd weights (256 - wx, wx). Halves of consecutive groups are adjacent, so a 256-bit load
  // takes one half of two groups. x_groups stops at the first group that does not fit (a source
  // row narrower than 16, or more than 2x downscaling); the outputs after it go scalar.
  int x_groups = 0;
  std::vector<std::int32_t> x_group_start;
  std::vector<std::uint8_t> x_group_shuffle;
  std::vector<std::int16_t> x_group_weight;

  // The x taps for 512-bit kernels (simd/resize_bilinear_rows/x86_avx512bw.hpp): wide group g = the
  // 16 outputs from x_wide_first[g], whose taps all lie in the 32 source pixels from
  // x_wide_start[g]. Groups start every 16 outputs, the last one at dst_width - 16 (overlapping
  // its neighbour), so they cover the whole row. For output k of group g, the 32 int16 at
  // x_wide_index[g * 32] hold sx - start, sx + 1 - start at 2k, 2k + 1 (a vpermw index) and
  // x_wide_weight[g * 32] the pmaddwd weights (256 - wx, wx). x_wide_groups is 0 when any group
  // does not fit (dst_width < 16, src_width < 32, or more than about 2x downscaling).
  int x_wide_groups = 0;
  std::vector<std::int32_t> x_wide_first;
  std::vector<std::int32_t> x_wide_start;
  std::vector<std::int16_t> x_wide_index;
  std::vector<std::int16_t> x_wide_weight;
};

ResizePlan make_resize_plan(int src_width, int src_height, int dst_width, int dst_height);

// Writes dst rows [y_begin, y_end). dst is plan.dst_width x plan.dst_height, src the plan's
// source size. Reads only src rows y_index[y], y_index[y] + 1 of those rows.
void resize_bilinear_rows_scalar(ImageView src, const ResizePlan& plan, MutableImageView dst,
                                 int y_begin, int y_end);

// Outputs [x_begin, x_end) of one dst row from its source rows top, bottom and the row's weight
// wy: the scalar formula, which the vector kernels call for the pixels after their last group.
void resize_bilinear_span_scalar(const std::uint8_t* top, const std::uint8_t* bottom,
                                 const ResizePlan& plan, std::uint32_t wy, int x_begin, int x_end,
                                 std::uint8_t* out);

}  // namespace aief

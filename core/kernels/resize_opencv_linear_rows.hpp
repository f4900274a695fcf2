#pragma once
// cv::resize(src, dst, size, 0, 0, INTER_LINEAR) on 8-bit gray images, to the byte: the pyramid
// of ORB-SLAM2/3's ComputePyramid, which resizes each level from the one above
// (docs/design.md §2, "ORB-SLAM's own pixels"). OpenCV 4's arithmetic (imgproc/src/resize.cpp):
//   scale   = 1 / (double(dst) / src)                                 per axis, in double
//   f       = float((i + 0.5) * scale - 0.5),  s = floor(f),  f -= s
//   columns: s < 0 -> s = 0, f = 0;  s >= src - 1 -> s = src - 1, f = 0   (rows are not clamped)
//   11-bit coefficients: c0 = saturate_cast<short>((1.f - f) * 2048), c1 = ...(f * 2048)
//   h(row)  = row[s] * a0 + row[min(s + 1, src - 1)] * a1                   (exact int)
//   rows r0 = clamp(s, 0, src - 1), r1 = clamp(s + 1, 0, src - 1)
//   dst     = ((h(r0) >> 4) * b0 >> 16) + ((h(r1) >> 4) * b1 >> 16) + 2) >> 2
// The last line is OpenCV's vector vertical pass (VResizeLinearVec_32s8u: v_mul_hi of the 16-bit
// h >> 4, then v_rshr_pack_u<2>), which rounds differently from its scalar formula
// (h0 * b0 + h1 * b1 + 2^21) >> 22; measured on the OpenCV this repository builds against
// (Debian's 4.6, x86-64), every column of every size takes the vector one, also the columns a
// 16-byte loop would leave to a scalar tail, also exact halvings (INTER_AREA there). Integers
// only, so one answer in every build; tests/test_faithful_mode.cpp checks it against
// cv::resize on random sizes, scale factors and images.
//
// Bounds: 0 <= a0, a1, b0, b1 <= 2048, so h <= 255 * 2048 and h >> 4 <= 32640 fits int16, each
// product term is <= 1020 and the sum before the last shift fits int16 too: the vector kernels
// (simd/resize_opencv_linear_rows/x86.hpp, neon.hpp) keep h >> 4 in int16 lanes and take the
// vertical pass as a 16-bit high multiply, exactly as OpenCV's vector code does.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"

namespace aief {

struct OpenCvResizePlan {
  int src_width = 0, src_height = 0, dst_width = 0, dst_height = 0;
  std::vector<std::int32_t> x_left, x_right;   // source columns of the two taps
  std::vector<std::int16_t> x_coef0, x_coef1;  // their 11-bit coefficients
  std::vector<std::int32_t> y_top, y_bottom;   // source rows of the two taps (clamped)
  std::vector<std::int16_t> y_coef0, y_coef1;

  // The x taps again, for the vector kernels' horizontal pass, outputs [0, 8 * x_groups): group
  // g = outputs 8g .. 8g + 7, whose taps all lie in the 16 source bytes from x_group_start[g]
  // (<= src_width - 16). Half h (0: outputs 8g .. 8g + 3, 1: 8g + 4 .. 8g + 7) of group g has 16
  // bytes at x_group_shuffle[(h * x_groups + g) * 16], a pshufb / tbl mask putting the two taps
  // of each output into the low bytes of two u16 lanes (s - start, 0x80, s1 - start, 0x80), and
  // 8 int16 at x_group_coef[(h * x_groups + g) * 8], the matching pmaddwd pairs (a0, a1). Halves
  // of consecutive groups are adjacent, so a 256-bit load takes one half of two groups. x_groups
  // stops at the first group that does not fit (a source row narrower than 16, or more than about
  // 2x downscaling); the outputs after it take the scalar span.
  int x_groups = 0;
  std::vector<std::int32_t> x_group_start;
  std::vector<std::uint8_t> x_group_shuffle;
  std::vector<std::int16_t> x_group_coef;
};

OpenCvResizePlan make_opencv_resize_plan(int src_width, int src_height, int dst_width,
                                         int dst_height);

// Writes dst rows [y_begin, y_end); src and dst have the plan's sizes (each side >= 1).
void resize_opencv_linear_rows_scalar(ImageView src, const OpenCvResizePlan& plan,
                                      MutableImageView dst, int y_begin, int y_end);

// The two passes of one output row, for the outputs [x_begin, x_end): the horizontal pass writes
// h >> 4 of source row `row` (int16, indexed by output column), the vertical pass combines two of
// those rows with the output row's (b0, b1). The vector kernels call them for their tails.
void resize_opencv_horizontal_span_scalar(const std::uint8_t* row, const OpenCvResizePlan& plan,
                                          int x_begin, int x_end, std::int16_t* out);
void resize_opencv_vertical_span_scalar(const std::int16_t* top, const std::int16_t* bottom,
                                        std::int16_t b0, std::int16_t b1, int x_begin, int x_end,
                                        std::uint8_t* out);

// The row loop every kernel shares: each output row takes its two source rows' horizontal passes
// from two buffers that remember which source row they hold (consecutive output rows share a
// source row most of the time, as OpenCV reuses its row buffers), then the vertical pass.
// horizontal(row, out) and vertical(top, bottom, b0, b1, out) cover the whole output row.
template <class Horizontal, class Vertical>
void resize_opencv_rows_with(ImageView src, const OpenCvResizePlan& plan, MutableImageView dst,
                             int y_begin, int y_end, Horizontal horizontal, Vertical vertical) {
  const std::size_t columns = static_cast<std::size_t>(plan.dst_width);
  std::vector<std::int16_t> buffer(2 * columns);
  std::int16_t* rows[2] = {buffer.data(), buffer.data() + columns};
  int source_of[2] = {-1, -1};
  const auto horizontal_of = [&](int source_row) -> const std::int16_t* {
    for (int k = 0; k < 2; ++k)
      if (source_of[k] == source_row) return rows[k];
    // Replace the buffer whose row is not the other tap of this output (the older one).
    const int k = source_of[0] < source_of[1] ? 0 : 1;
    horizontal(src.row(source_row), rows[k]);
    source_of[k] = source_row;
    return rows[k];
  };
  for (int y = y_begin; y < y_end; ++y) {
    const auto i = static_cast<std::size_t>(y);
    // Source rows ascend with y, so the buffer the bottom tap replaces is never the top tap's.
    const std::int16_t* top = horizontal_of(plan.y_top[i]);
    const std::int16_t* bottom = horizontal_of(plan.y_bottom[i]);
    vertical(top, bottom, plan.y_coef0[i], plan.y_coef1[i], dst.row(y));
  }
}

}  // namespace aief

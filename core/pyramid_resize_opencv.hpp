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
};

OpenCvResizePlan make_opencv_resize_plan(int src_width, int src_height, int dst_width,
                                         int dst_height);

// Writes dst rows [y_begin, y_end); src and dst have the plan's sizes (each side >= 1).
void resize_opencv_linear_rows(ImageView src, const OpenCvResizePlan& plan, MutableImageView dst,
                               int y_begin, int y_end);

}  // namespace aief

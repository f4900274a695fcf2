#include "core/pyramid_resize_opencv.hpp"

#include <algorithm>
#include <cmath>

namespace aief {

namespace {

constexpr int kCoefBits = 11;  // OpenCV's INTER_RESIZE_COEF_BITS
constexpr float kCoefScale = static_cast<float>(1 << kCoefBits);

// saturate_cast<short>(float): cvRound (round half to even), then saturate.
std::int16_t coefficient(float value) {
  const long rounded = std::lrint(value * kCoefScale);
  return static_cast<std::int16_t>(std::clamp(rounded, -32768L, 32767L));
}

struct Tap {
  int s;
  float f;
};

// OpenCV's source position of output i: float((i + 0.5) * scale - 0.5), floor and fraction.
Tap tap(int i, double scale) {
  float f = static_cast<float>((i + 0.5) * scale - 0.5);
  const int s = static_cast<int>(std::floor(f));
  f -= static_cast<float>(s);
  return {s, f};
}

}  // namespace

OpenCvResizePlan make_opencv_resize_plan(int src_width, int src_height, int dst_width,
                                         int dst_height) {
  OpenCvResizePlan plan;
  plan.src_width = src_width;
  plan.src_height = src_height;
  plan.dst_width = dst_width;
  plan.dst_height = dst_height;
  // cv::resize passes inv_scale = double(dst) / src, hal::resize takes 1 / inv_scale.
  const double scale_x = 1.0 / (static_cast<double>(dst_width) / src_width);
  const double scale_y = 1.0 / (static_cast<double>(dst_height) / src_height);
  const auto columns = static_cast<std::size_t>(dst_width);
  plan.x_left.resize(columns);
  plan.x_right.resize(columns);
  plan.x_coef0.resize(columns);
  plan.x_coef1.resize(columns);
  for (int x = 0; x < dst_width; ++x) {
    Tap t = tap(x, scale_x);
    if (t.s < 0) t = {0, 0.0f};
    if (t.s >= src_width - 1) t = {src_width - 1, 0.0f};
    const auto i = static_cast<std::size_t>(x);
    plan.x_left[i] = t.s;
    plan.x_right[i] = std::min(t.s + 1, src_width - 1);
    plan.x_coef0[i] = coefficient(1.0f - t.f);
    plan.x_coef1[i] = coefficient(t.f);
  }
  const auto rows = static_cast<std::size_t>(dst_height);
  plan.y_top.resize(rows);
  plan.y_bottom.resize(rows);
  plan.y_coef0.resize(rows);
  plan.y_coef1.resize(rows);
  for (int y = 0; y < dst_height; ++y) {
    const Tap t = tap(y, scale_y);
    const auto i = static_cast<std::size_t>(y);
    plan.y_top[i] = std::clamp(t.s, 0, src_height - 1);
    plan.y_bottom[i] = std::clamp(t.s + 1, 0, src_height - 1);
    plan.y_coef0[i] = coefficient(1.0f - t.f);
    plan.y_coef1[i] = coefficient(t.f);
  }
  return plan;
}

void resize_opencv_linear_rows(ImageView src, const OpenCvResizePlan& plan, MutableImageView dst,
                               int y_begin, int y_end) {
  const std::size_t columns = static_cast<std::size_t>(plan.dst_width);
  // Two horizontal rows, each remembered with its source row: consecutive outputs share a source
  // row most of the time (as OpenCV reuses its row buffers).
  std::vector<std::int32_t> rows[2] = {std::vector<std::int32_t>(columns),
                                       std::vector<std::int32_t>(columns)};
  int source_of[2] = {-1, -1};
  const auto horizontal = [&](int source_row) -> const std::int32_t* {
    for (int k = 0; k < 2; ++k)
      if (source_of[k] == source_row) return rows[k].data();
    // Replace the buffer whose row is not the other tap of this output (the older one).
    const int k = source_of[0] < source_of[1] ? 0 : 1;
    const std::uint8_t* row = src.row(source_row);
    std::int32_t* out = rows[k].data();
    for (std::size_t x = 0; x < columns; ++x)
      out[x] = row[plan.x_left[x]] * plan.x_coef0[x] + row[plan.x_right[x]] * plan.x_coef1[x];
    source_of[k] = source_row;
    return out;
  };
  for (int y = y_begin; y < y_end; ++y) {
    const auto i = static_cast<std::size_t>(y);
    // Source rows ascend with y, so the buffer the bottom tap replaces is never the top tap's.
    const std::int32_t* top = horizontal(plan.y_top[i]);
    const std::int32_t* bottom = horizontal(plan.y_bottom[i]);
    const std::int32_t b0 = plan.y_coef0[i], b1 = plan.y_coef1[i];
    std::uint8_t* out = dst.row(y);
    for (std::size_t x = 0; x < columns; ++x) {
      // v_mul_hi of the 16-bit h >> 4 (h <= 255 * 2048, so h >> 4 fits), then v_rshr_pack_u<2>.
      const std::int32_t sum = ((top[x] >> 4) * b0 >> 16) + ((bottom[x] >> 4) * b1 >> 16);
      out[x] = static_cast<std::uint8_t>(std::clamp((sum + 2) >> 2, 0, 255));
    }
  }
}

}  // namespace aief

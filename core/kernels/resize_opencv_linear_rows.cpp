#include "core/kernels/resize_opencv_linear_rows.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/kernels/kernel_evidence.hpp"

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

// The grouped x taps of the vector kernels (see OpenCvResizePlan).
void x_groups_plan(OpenCvResizePlan& plan) {
  constexpr int kGroup = 8, kWindow = 16;
  int groups = 0;
  if (plan.src_width >= kWindow) {
    for (; (groups + 1) * kGroup <= plan.dst_width; ++groups) {
      const auto first = static_cast<std::size_t>(groups * kGroup);
      // At the right edge the taps clamp to the last column: the window moves left to stay inside.
      const int start = std::min(plan.x_left[first], plan.src_width - kWindow);
      if (plan.x_right[first + kGroup - 1] - start >= kWindow) break;
    }
  }
  plan.x_groups = groups;
  plan.x_group_start.resize(static_cast<std::size_t>(groups));
  plan.x_group_shuffle.resize(static_cast<std::size_t>(groups) * 2 * 16);
  plan.x_group_coef.resize(static_cast<std::size_t>(groups) * 2 * 8);
  for (int g = 0; g < groups; ++g) {
    const auto first = static_cast<std::size_t>(g * kGroup);
    const int start = std::min(plan.x_left[first], plan.src_width - kWindow);
    plan.x_group_start[static_cast<std::size_t>(g)] = start;
    for (int i = 0; i < kGroup; ++i) {
      const std::size_t x = first + static_cast<std::size_t>(i);
      const std::size_t half_row = static_cast<std::size_t>((i / 4) * groups + g);
      const int k = i % 4;
      std::uint8_t* shuffle =
          &plan.x_group_shuffle[half_row * 16 + 4 * static_cast<std::size_t>(k)];
      shuffle[0] = static_cast<std::uint8_t>(plan.x_left[x] - start);
      shuffle[1] = 0x80;
      shuffle[2] = static_cast<std::uint8_t>(plan.x_right[x] - start);
      shuffle[3] = 0x80;
      std::int16_t* coef = &plan.x_group_coef[half_row * 8 + 2 * static_cast<std::size_t>(k)];
      coef[0] = plan.x_coef0[x];
      coef[1] = plan.x_coef1[x];
    }
  }
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
  x_groups_plan(plan);
  return plan;
}

void resize_opencv_horizontal_span_scalar(const std::uint8_t* row, const OpenCvResizePlan& plan,
                                          int x_begin, int x_end, std::int16_t* out) {
  for (int x = x_begin; x < x_end; ++x) {
    const auto i = static_cast<std::size_t>(x);
    const std::int32_t h =
        row[plan.x_left[i]] * plan.x_coef0[i] + row[plan.x_right[i]] * plan.x_coef1[i];
    out[x] = static_cast<std::int16_t>(h >> 4);  // h <= 255 * 2048: h >> 4 fits (header)
  }
}

void resize_opencv_vertical_span_scalar(const std::int16_t* top, const std::int16_t* bottom,
                                        std::int16_t b0, std::int16_t b1, int x_begin, int x_end,
                                        std::uint8_t* out) {
  for (int x = x_begin; x < x_end; ++x) {
    // v_mul_hi of the 16-bit h >> 4, then v_rshr_pack_u<2>.
    const std::int32_t sum = (top[x] * b0 >> 16) + (bottom[x] * b1 >> 16);
    out[x] = static_cast<std::uint8_t>(std::clamp((sum + 2) >> 2, 0, 255));
  }
}

void resize_opencv_linear_rows_scalar(ImageView src, const OpenCvResizePlan& plan,
                                      MutableImageView dst, int y_begin, int y_end) {
  const int columns = plan.dst_width;
  resize_opencv_rows_with(
      src, plan, dst, y_begin, y_end,
      [&](const std::uint8_t* row, std::int16_t* out) {
        resize_opencv_horizontal_span_scalar(row, plan, 0, columns, out);
      },
      [&](const std::int16_t* top, const std::int16_t* bottom, std::int16_t b0, std::int16_t b1,
          std::uint8_t* out) {
        resize_opencv_vertical_span_scalar(top, bottom, b0, b1, 0, columns, out);
      });
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_resize_opencv_linear_rows(const KernelTable& scalar, const KernelTable& other,
                                            const GrayImage& src) {
  // ORB-SLAM's pyramid ratio (cvRound of the size over 1.2), the options' range of ratios, an
  // exact halving, and upscaling (cv::resize's any ratio; no group fits past about 2x down).
  for (double ratio : {1.2, 1.01, 1.5, 2.0, 2.7, 4.0, 0.6}) {
    const int w = std::max(1, static_cast<int>(std::lround(src.width() / ratio)));
    const int h = std::max(1, static_cast<int>(std::lround(src.height() / ratio)));
    const OpenCvResizePlan plan = make_opencv_resize_plan(src.width(), src.height(), w, h);
    GrayImage a(w, h), b(w, h);
    scalar.resize_opencv_linear_rows(src.view(), plan, a.mutable_view(), 0, h);
    // The other kernel in two bands, the second starting on its own row buffers.
    other.resize_opencv_linear_rows(src.view(), plan, b.mutable_view(), 0, h / 2);
    other.resize_opencv_linear_rows(src.view(), plan, b.mutable_view(), h / 2, h);
    const std::string difference = first_difference_of_images(a, b, other.name);
    if (!difference.empty())
      return where(src, "ratio " + std::to_string(ratio) + " -> " + difference);
  }
  return "";
}

// Every level of the pyramid from the one above.
KernelWorkload workload_resize_opencv_linear_rows(const KernelBenchInputs& in,
                                                  const KernelTable& k) {
  return {[&in, &k, out = images_of_the_same_sizes(in.levels)]() mutable {
            for (std::size_t n = 1; n < in.levels.size(); ++n)
              k.resize_opencv_linear_rows(in.levels[n - 1].view(), in.opencv_plans[n],
                                          out[n].mutable_view(), 0, out[n].height());
          },
          in.pixels - static_cast<long long>(in.levels[0].width()) * in.levels[0].height()};
}

}  // namespace aief

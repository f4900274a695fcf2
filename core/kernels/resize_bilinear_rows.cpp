#include "core/kernels/resize_bilinear_rows.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>
#include <utility>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

namespace {

// One axis of the plan: left/top tap and Q8 weight of the right/bottom tap.
void axis_plan(int src, int dst, std::vector<std::int32_t>& index,
               std::vector<std::uint16_t>& weight) {
  index.resize(static_cast<std::size_t>(dst));
  weight.resize(static_cast<std::size_t>(dst));
  const double scale = static_cast<double>(src) / static_cast<double>(dst);
  for (int i = 0; i < dst; ++i) {
    const double f = (i + 0.5) * scale - 0.5;
    int s = static_cast<int>(std::floor(f));
    int w = static_cast<int>(std::lround((f - s) * 256.0));
    if (w == 256) {
      ++s;
      w = 0;
    }
    if (s < 0) {
      s = 0;
      w = 0;
    }
    if (s > src - 2) {
      w = s >= src - 1 ? 256 : w;
      s = src - 2;
    }
    index[static_cast<std::size_t>(i)] = s;
    weight[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(w);
  }
}

// The grouped x taps of the vector kernel (see ResizePlan).
void x_groups_plan(ResizePlan& plan) {
  constexpr int kGroup = 8, kWindow = 16;
  const int src = plan.src_width;
  int groups = 0;
  if (src >= kWindow)
    for (; (groups + 1) * kGroup <= plan.dst_width; ++groups) {
      const int first = plan.x_index[static_cast<std::size_t>(groups * kGroup)];
      const int last = plan.x_index[static_cast<std::size_t>(groups * kGroup + kGroup - 1)];
      if (last + 1 >= std::min(first, src - kWindow) + kWindow)
        break;  // the right tap of the last output must be inside
    }
  plan.x_groups = groups;
  plan.x_group_start.resize(static_cast<std::size_t>(groups));
  plan.x_group_shuffle.resize(static_cast<std::size_t>(groups) * 2 * 16);
  plan.x_group_weight.resize(static_cast<std::size_t>(groups) * 2 * 8);
  for (int g = 0; g < groups; ++g) {
    const int start = std::min(plan.x_index[static_cast<std::size_t>(g * kGroup)], src - kWindow);
    plan.x_group_start[static_cast<std::size_t>(g)] = start;
    for (int i = 0; i < kGroup; ++i) {
      const std::size_t x = static_cast<std::size_t>(g * kGroup + i);
      const std::size_t half_row = static_cast<std::size_t>((i / 4) * groups + g),
                        k = static_cast<std::size_t>(i % 4);
      std::uint8_t* shuffle = &plan.x_group_shuffle[half_row * 16 + 4 * k];
      shuffle[0] = static_cast<std::uint8_t>(plan.x_index[x] - start);
      shuffle[1] = 0x80;
      shuffle[2] = static_cast<std::uint8_t>(plan.x_index[x] + 1 - start);
      shuffle[3] = 0x80;
      std::int16_t* weight = &plan.x_group_weight[half_row * 8 + 2 * k];
      weight[0] = static_cast<std::int16_t>(256 - plan.x_weight[x]);
      weight[1] = static_cast<std::int16_t>(plan.x_weight[x]);
    }
  }
}

// The wide x groups of the 512-bit kernel (see ResizePlan).
void x_wide_groups_plan(ResizePlan& plan) {
  constexpr int kGroup = 16, kWindow = 32;
  const int src = plan.src_width, dst = plan.dst_width;
  if (src < kWindow || dst < kGroup) return;
  const int groups = (dst + kGroup - 1) / kGroup;
  std::vector<std::int32_t> first(static_cast<std::size_t>(groups)),
      start(static_cast<std::size_t>(groups));
  for (int g = 0; g < groups; ++g) {
    const int x0 = std::min(g * kGroup, dst - kGroup);
    const int s = std::min(plan.x_index[static_cast<std::size_t>(x0)], src - kWindow);
    if (plan.x_index[static_cast<std::size_t>(x0 + kGroup - 1)] + 1 >= s + kWindow)
      return;  // a tap outside the window
    first[static_cast<std::size_t>(g)] = x0;
    start[static_cast<std::size_t>(g)] = s;
  }
  plan.x_wide_groups = groups;
  plan.x_wide_first = std::move(first);
  plan.x_wide_start = std::move(start);
  plan.x_wide_index.resize(static_cast<std::size_t>(groups) * kWindow);
  plan.x_wide_weight.resize(static_cast<std::size_t>(groups) * kWindow);
  for (int g = 0; g < groups; ++g)
    for (int k = 0; k < kGroup; ++k) {
      const std::size_t x =
          static_cast<std::size_t>(plan.x_wide_first[static_cast<std::size_t>(g)] + k);
      const std::size_t at = static_cast<std::size_t>(g * kWindow + 2 * k);
      const int sx = plan.x_index[x] - plan.x_wide_start[static_cast<std::size_t>(g)];
      plan.x_wide_index[at] = static_cast<std::int16_t>(sx);
      plan.x_wide_index[at + 1] = static_cast<std::int16_t>(sx + 1);
      plan.x_wide_weight[at] = static_cast<std::int16_t>(256 - plan.x_weight[x]);
      plan.x_wide_weight[at + 1] = static_cast<std::int16_t>(plan.x_weight[x]);
    }
}

}  // namespace

ResizePlan make_resize_plan(int src_width, int src_height, int dst_width, int dst_height) {
  assert(src_width >= 2 && src_height >= 2 && dst_width >= 1 && dst_height >= 1);
  ResizePlan plan;
  plan.src_width = src_width;
  plan.src_height = src_height;
  plan.dst_width = dst_width;
  plan.dst_height = dst_height;
  axis_plan(src_width, dst_width, plan.x_index, plan.x_weight);
  axis_plan(src_height, dst_height, plan.y_index, plan.y_weight);
  x_groups_plan(plan);
  x_wide_groups_plan(plan);
  return plan;
}

void resize_bilinear_span_scalar(const std::uint8_t* top, const std::uint8_t* bottom,
                                 const ResizePlan& plan, std::uint32_t wy, int x_begin, int x_end,
                                 std::uint8_t* out) {
  for (int x = x_begin; x < x_end; ++x) {
    const int sx = plan.x_index[static_cast<std::size_t>(x)];
    const std::uint32_t wx = plan.x_weight[static_cast<std::size_t>(x)];
    const std::uint32_t h0 = top[sx] * (256 - wx) + top[sx + 1] * wx;
    const std::uint32_t h1 = bottom[sx] * (256 - wx) + bottom[sx + 1] * wx;
    out[x] = static_cast<std::uint8_t>((h0 * (256 - wy) + h1 * wy + 32768) >> 16);
  }
}

void resize_bilinear_rows_scalar(ImageView src, const ResizePlan& plan, MutableImageView dst,
                                 int y_begin, int y_end) {
  for (int y = y_begin; y < y_end; ++y) {
    const int sy = plan.y_index[static_cast<std::size_t>(y)];
    resize_bilinear_span_scalar(src.row(sy), src.row(sy + 1), plan,
                                plan.y_weight[static_cast<std::size_t>(y)], 0, plan.dst_width,
                                dst.row(y));
  }
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_resize_bilinear_rows(const KernelTable& scalar, const KernelTable& other,
                                       const GrayImage& src) {
  if (src.width() < 2 || src.height() < 2) return "";
  // Every pyramid ratio the options allow, from just above 1 to 4 (scale_factor is in (1, 4]).
  for (double ratio : {1.01, 1.2, 1.5, 2.0, 2.7, 4.0}) {
    const int w = std::max(1, static_cast<int>(std::lround(src.width() / ratio)));
    const int h = std::max(1, static_cast<int>(std::lround(src.height() / ratio)));
    const ResizePlan plan = make_resize_plan(src.width(), src.height(), w, h);
    GrayImage a(w, h), b(w, h);
    scalar.resize_bilinear_rows(src.view(), plan, a.mutable_view(), 0, h);
    other.resize_bilinear_rows(src.view(), plan, b.mutable_view(), 0, h);
    const std::string difference = first_difference_of_images(a, b, other.name);
    if (!difference.empty())
      return where(src, "ratio " + std::to_string(ratio) + " -> " + difference);
  }
  return "";
}

// Every level of the pyramid from the one above.
KernelWorkload workload_resize_bilinear_rows(const KernelBenchInputs& in, const KernelTable& k) {
  return {[&in, &k, out = images_of_the_same_sizes(in.levels)]() mutable {
            for (std::size_t n = 1; n < in.levels.size(); ++n)
              k.resize_bilinear_rows(in.levels[n - 1].view(), in.plans[n], out[n].mutable_view(), 0,
                                     out[n].height());
          },
          in.pixels - static_cast<long long>(in.levels[0].width()) * in.levels[0].height()};
}

}  // namespace aief

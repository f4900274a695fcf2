#include "core/pyramid_resize.hpp"

#include <cassert>
#include <cmath>

namespace aief {

namespace {

// One axis of the plan: left/top tap and Q8 weight of the right/bottom tap.
void axis_plan(int src, int dst, std::vector<std::int32_t>& index, std::vector<std::uint16_t>& weight) {
  index.resize(static_cast<std::size_t>(dst));
  weight.resize(static_cast<std::size_t>(dst));
  const double scale = static_cast<double>(src) / static_cast<double>(dst);
  for (int i = 0; i < dst; ++i) {
    const double f = (i + 0.5) * scale - 0.5;
    int s = static_cast<int>(std::floor(f));
    int w = static_cast<int>(std::lround((f - s) * 256.0));
    if (w == 256) { ++s; w = 0; }
    if (s < 0) { s = 0; w = 0; }
    if (s > src - 2) { w = s >= src - 1 ? 256 : w; s = src - 2; }
    index[static_cast<std::size_t>(i)] = s;
    weight[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(w);
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
  return plan;
}

void resize_bilinear_rows_scalar(ImageView src, const ResizePlan& plan, MutableImageView dst, int y_begin, int y_end) {
  const int width = plan.dst_width;
  for (int y = y_begin; y < y_end; ++y) {
    const int sy = plan.y_index[static_cast<std::size_t>(y)];
    const std::uint32_t wy = plan.y_weight[static_cast<std::size_t>(y)];
    const std::uint8_t* top = src.row(sy);
    const std::uint8_t* bottom = src.row(sy + 1);
    std::uint8_t* out = dst.row(y);
    for (int x = 0; x < width; ++x) {
      const int sx = plan.x_index[static_cast<std::size_t>(x)];
      const std::uint32_t wx = plan.x_weight[static_cast<std::size_t>(x)];
      const std::uint32_t h0 = top[sx] * (256 - wx) + top[sx + 1] * wx;
      const std::uint32_t h1 = bottom[sx] * (256 - wx) + bottom[sx + 1] * wx;
      out[x] = static_cast<std::uint8_t>((h0 * (256 - wy) + h1 * wy + 32768) >> 16);
    }
  }
}

}  // namespace aief

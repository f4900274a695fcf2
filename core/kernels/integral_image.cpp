#include "core/kernels/integral_image.hpp"

namespace aief {

void IntegralImage::compute(ImageView image) {
  width_ = image.width;
  height_ = image.height;
  const std::size_t stride = static_cast<std::size_t>(width_) + 1;
  entries_.resize(stride * (static_cast<std::size_t>(height_) + 1));
  std::uint32_t* above = entries_.data();
  for (std::size_t x = 0; x < stride; ++x) above[x] = 0;
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* pixels = image.row(y);
    std::uint32_t* out = above + stride;
    std::uint32_t row_sum = 0;
    out[0] = 0;
    for (int x = 0; x < width_; ++x) {
      row_sum += pixels[x];
      out[x + 1] = above[x + 1] + row_sum;
    }
    above = out;
  }
}

}  // namespace aief

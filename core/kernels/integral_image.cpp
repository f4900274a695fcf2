#include "core/kernels/integral_image.hpp"

#include "core/kernels/integral_image_row.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

namespace {

template <class Row>
void compute_rows(ImageView image, Row row, std::vector<std::uint32_t>& entries) {
  const std::size_t stride = static_cast<std::size_t>(image.width) + 1;
  entries.resize(stride * (static_cast<std::size_t>(image.height) + 1));
  std::uint32_t* above = entries.data();
  for (std::size_t x = 0; x < stride; ++x) above[x] = 0;
  for (int y = 0; y < image.height; ++y) {
    std::uint32_t* out = above + stride;
    row(image.row(y), image.width, above, out);
    above = out;
  }
}

}  // namespace

void IntegralImage::compute(ImageView image, const KernelTable& kernels) {
  width_ = image.width;
  height_ = image.height;
  compute_rows(image, kernels.integral_image_row, entries_);
}

void IntegralImage::compute(ImageView image) {
  width_ = image.width;
  height_ = image.height;
  compute_rows(image, &integral_image_row_scalar, entries_);
}

}  // namespace aief

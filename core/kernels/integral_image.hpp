#pragma once
// The integral image the box descriptor reads (core/kernels/box_describe.hpp): (W + 1) x (H + 1)
// entries, entry (y, x) = the sum of the pixels in rows [0, y) and columns [0, x), row 0 and
// column 0 zero. Held modulo 2^32 (uint32 wraps): a box's sum, four entries added and subtracted,
// is exact in uint32 arithmetic whenever the box holds fewer than 2^32 / 255 pixels, which every
// box of a descriptor does (the largest, radius 16 at scale 4, is 131 x 131 pixels).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "aief/image.hpp"

namespace aief {

struct KernelTable;

// Read-only view of an integral image, or of a band of its rows: entry (y, x) at
// data[(y - first_row) * stride + x], x in [0, width], y in [first_row, first_row + the rows held]
// within [0, height] (width and height are the image's). A band may be taken from any origin row
// above it (its first row need not be zero): a box's sum is a difference of entries in the same
// columns, so a constant per column cancels, and every box inside the band sums alike.
struct IntegralView {
  const std::uint32_t* data = nullptr;
  int width = 0;              // of the image: width + 1 entries a row
  int height = 0;             // of the image: height + 1 rows
  std::ptrdiff_t stride = 0;  // entries between the starts of two rows, >= width + 1
  int first_row = 0;          // the integral row held at data
  const std::uint32_t* row(int y) const { return data + (y - first_row) * stride; }
};

// An integral image that owns its entries and reuses them for images of a size it has held.
class IntegralImage {
 public:
  IntegralView view() const { return {entries_.data(), width_, height_, width_ + 1}; }
  // Computes the integral of `image`, a row at a time by `kernels`' integral_image_row
  // (core/kernels/integral_image_row.hpp; the same entries under every kernel set).
  void compute(ImageView image, const KernelTable& kernels);
  // The same with the scalar reference (tests, and inputs made outside a timed pass).
  void compute(ImageView image);

 private:
  std::vector<std::uint32_t> entries_;
  int width_ = 0, height_ = 0;
};

}  // namespace aief

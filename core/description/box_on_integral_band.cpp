#include "core/description/box_on_integral_band.hpp"

#include <algorithm>
#include <cstring>

#include "core/description/sliding_band.hpp"

namespace aief {

namespace {

// Rows of keypoints one band serves at a time. The integral band's rows are 4 bytes a pixel and
// the rows it keeps when it slides are moved, so it serves more rows at a time than rBRIEF's
// (core/description/rbrief_on_blurred_band.cpp): on a 1920 x 1080 frame in the quality mode, 96
// rows moved 11.4 M instructions of memmove a frame, 192 rows 5.7 M (docs/speed.md); the whole
// level's integral image held 46 MB.
constexpr int kBandKeypointRows = 192;

}  // namespace

int BoxOnIntegralBand::reach() {
  static const int reach = box_reach(kBoxLevelScale);  // computed once
  return reach;
}

void BoxOnIntegralBand::start(const LevelGeometry& geometry, Selections selections) {
  selections_ = selections;
  if (geometry.grid.count() > 0 && selections_ == Selections::one) {
    integral_band_rows_ = std::min(geometry.height + 1, kBandKeypointRows + 2 * reach() + 1);
    integral_band_.resize(static_cast<std::size_t>(integral_band_rows_) *
                          (static_cast<std::size_t>(geometry.width) + 1));
  }
  integral_ready_ = false;
}

void BoxOnIntegralBand::prepare_whole_input(const PyramidLevel& level, const KernelTable& kernels) {
  integral_.compute(level.pixels, kernels);
  integral_ready_ = true;
}

void BoxOnIntegralBand::describe(const PyramidLevel& level, const KernelTable& kernels,
                                 const PixelPoint* points, const float* angles_deg, int count,
                                 std::uint8_t* descriptors) {
  box_points_.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i)
    box_points_[static_cast<std::size_t>(i)] = {static_cast<float>(points[i].x),
                                                static_cast<float>(points[i].y)};
  if (selections_ == Selections::one) {
    describe_through_band(level, kernels, points, angles_deg, count, descriptors);
    return;
  }
  if (!whole_input_ready()) prepare_whole_input(level, kernels);
  kernels.box_describe(integral_.view(), box_points_.data(), angles_deg, count, kBoxLevelScale,
                       descriptors);
}

void BoxOnIntegralBand::describe_through_band(const PyramidLevel& level, const KernelTable& kernels,
                                              const PixelPoint* points, const float* angles_deg,
                                              int count, std::uint8_t* descriptors) {
  // Integral rows [top, end) from the origin row of the band's first fill (zeros; entry
  // differences within the band are the integral's, core/kernels/integral_image.hpp): a point
  // far below the band starts a new origin, so rows between points are never summed.
  const int width = level.geometry.width, height = level.geometry.height;
  const std::ptrdiff_t stride = width + 1;
  std::uint32_t* band = integral_band_.data();
  const auto row = [&](int r) { return band + r * stride; };  // band row r
  const auto make_rows = [&](int top, int new_top, int kept_end, int new_end) {
    int r = kept_end;
    if (kept_end > new_top) {
      std::memmove(band, row(new_top - top),
                   static_cast<std::size_t>(kept_end - new_top) * static_cast<std::size_t>(stride) *
                       sizeof(std::uint32_t));
    } else {
      std::fill(band, band + stride, 0u);
      ++r;
    }
    for (; r < new_end; ++r)
      kernels.integral_image_row(level.pixels.row(r - 1), width, row(r - 1 - new_top),
                                 row(r - new_top));
  };
  const auto describe = [&](int first, int last, int top) {
    kernels.box_describe({band, width, height, stride, top}, box_points_.data() + first,
                         angles_deg + first, last - first, kBoxLevelScale,
                         descriptors + static_cast<std::size_t>(first) * kDescriptorBytes);
  };
  describe_through_sliding_band(points, count, reach(), height + 1, integral_band_rows_, make_rows,
                                describe);
}

}  // namespace aief

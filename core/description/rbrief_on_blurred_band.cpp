#include "core/description/rbrief_on_blurred_band.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>

#include "core/description/patch_blur.hpp"
#include "core/description/sliding_band.hpp"

namespace aief {

namespace {

// Rows of keypoints one band serves at a time; the band adds reach() rows above and below.
constexpr int kBandKeypointRows = 96;

}  // namespace

void RbriefOnBlurredBand::start(const LevelGeometry& geometry, Selections selections) {
  selections_ = selections;
  if (geometry.grid.count() > 0) {  // a level too small to use is never described
    if (selections_ == Selections::many)
      blurred_.resize(geometry.width, geometry.height);
    else
      blurred_.resize(geometry.width, std::min(geometry.height, kBandKeypointRows + 2 * reach()));
  }
  blurred_top_ = blurred_end_ = 0;
}

void RbriefOnBlurredBand::prepare_whole_input(const PyramidLevel& level,
                                              const KernelTable& kernels) {
  assert(selections_ == Selections::many);
  kernels.gaussian7_rows(level.pixels, blurred_.mutable_view(), 0, level.geometry.height, 0,
                         level.geometry.width);
  blurred_end_ = level.geometry.height;
}

void RbriefOnBlurredBand::describe(const PyramidLevel& level, const KernelTable& kernels,
                                   const PixelPoint* points, const float* angles_deg, int count,
                                   std::uint8_t* descriptors) {
  if (selections_ == Selections::one) {
    describe_through_band(level, kernels, points, angles_deg, count, descriptors);
    return;
  }
  if (!whole_input_ready()) prepare_whole_input(level, kernels);
  kernels.rbrief_describe(blurred_.view(), points, angles_deg, count, descriptors);
}

void RbriefOnBlurredBand::describe_through_band(const PyramidLevel& level,
                                                const KernelTable& kernels,
                                                const PixelPoint* points, const float* angles_deg,
                                                int count, std::uint8_t* descriptors) {
  // The blurred rows only at the columns the points' patches cover
  // (core/description/patch_blur.hpp).
  const int width = level.geometry.width;
  const MutableImageView band = blurred_.mutable_view();
  std::vector<PixelPoint>& shifted = band_points_;
  shifted.resize(static_cast<std::size_t>(count));
  const auto make_rows = [&](int top, int new_top, int kept_end, int new_end) {
    if (kept_end > new_top)
      std::memmove(
          band.data, band.row(new_top - top),
          static_cast<std::size_t>(kept_end - new_top) * static_cast<std::size_t>(band.stride));
    blur_patch_rows(kernels, level.pixels,
                    {band.row(kept_end - new_top), width, new_end - kept_end, band.stride},
                    kept_end, new_end, points, count, blur_columns_);
    blurred_top_ = new_top;
    blurred_end_ = new_end;
  };
  const auto describe = [&](int first, int last, int top) {
    for (int i = first; i < last; ++i)
      shifted[static_cast<std::size_t>(i)] = {points[i].x, points[i].y - top};
    kernels.rbrief_describe({band.data, width, blurred_end_ - top, band.stride},
                            shifted.data() + first, angles_deg + first, last - first,
                            descriptors + static_cast<std::size_t>(first) * kDescriptorBytes);
  };
  describe_through_sliding_band(points, count, reach(), level.geometry.height, blurred_.height(),
                                make_rows, describe);
}

}  // namespace aief

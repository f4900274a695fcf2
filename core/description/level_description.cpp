#include "core/description/level_description.hpp"

#include "core/kernels/fast_atan2.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>

#include "core/description/patch_blur.hpp"
#include "core/kernels/ic_moments.hpp"

namespace aief {

namespace {

// Rows of keypoints one band serves at a time; the band adds the rows a describe reads above and
// below (kEdgeBorder for rBRIEF, box_reach for the box). The integral band's rows are 4 bytes a
// pixel and the rows it keeps when it slides are moved, so it serves more rows at a time: on a
// 1920 x 1080 frame in the quality mode, 96 rows moved 11.4 M instructions of memmove a frame, 192
// rows 5.7 M (docs/speed.md); the whole level's integral image held 46 MB.
constexpr int kBandKeypointRows = 96;
constexpr int kBoxBandKeypointRows = 192;

// Rows above and below a keypoint the box descriptor reads on its level (computed once).
int box_level_reach() {
  static const int reach = box_reach(kBoxLevelScale);
  return reach;
}

// The points come in raster order, so the rows they read, [y - reach, y + reach] (clipped to
// [0, rows)), form a window sliding down the level. A band of `capacity` rows holds rows [top,
// end); when a point needs a row below it, the points before it are described
// (describe(first, last, top)), and make_rows(top, new_top, kept_end, new_end) moves rows
// [new_top, kept_end), already made, to the band's start and makes rows [kept_end, new_end)
// after them: every row is made once, in a buffer that stays in cache, and rows no point reads
// are not made.
template <class MakeRows, class Describe>
void describe_through_sliding_band(const std::vector<PixelPoint>& points, int count, int reach,
                                   int rows, int capacity, MakeRows make_rows, Describe describe) {
  int top = 0, end = 0;
  int first = 0;  // first point not yet described
  for (int i = 0; i < count; ++i) {
    const int y = points[static_cast<std::size_t>(i)].y;
    if (std::min(rows, y + reach + 1) <= end) continue;
    if (i > first) describe(first, i, top);
    first = i;
    const int new_top = std::max(0, y - reach);
    const int new_end = std::min(rows, new_top + capacity);
    make_rows(top, new_top, std::max(new_top, end), new_end);
    top = new_top;
    end = new_end;
  }
  if (count > first) describe(first, count, top);
}

}  // namespace

void LevelDescriptions::start(const LevelGeometry& geometry, Selections selections) {
  selections_ = selections;
  const int w = geometry.width, h = geometry.height;
  if (geometry.grid.count() > 0 && descriptor_ == DescriptorKind::rbrief) {
    // a level too small to use is never described
    if (selections_ == Selections::many)
      blurred_.resize(w, h);
    else
      blurred_.resize(w, std::min(h, kBandKeypointRows + 2 * kEdgeBorder));
  }
  if (geometry.grid.count() > 0 && descriptor_ == DescriptorKind::box &&
      selections_ == Selections::one) {
    integral_band_rows_ = std::min(h + 1, kBoxBandKeypointRows + 2 * box_level_reach() + 1);
    integral_band_.resize(static_cast<std::size_t>(integral_band_rows_) *
                          (static_cast<std::size_t>(w) + 1));
  }
  blurred_top_ = blurred_end_ = 0;
  memo_slot_.clear();
  memo_angle_deg_.clear();
  memo_descriptor_.clear();
}

std::size_t LevelDescriptions::slot(std::int32_t i) const {
  const std::int32_t slot = memo_slot_[static_cast<std::size_t>(i)];
  assert(slot >= 0);
  return static_cast<std::size_t>(slot);
}

void LevelDescriptions::describe(const PyramidLevel& level,
                                 const std::vector<Candidate>& candidates,
                                 const std::vector<std::int32_t>& indices,
                                 const KernelTable& kernels) {
  points_.clear();
  todo_.clear();
  for (std::int32_t i : indices) {
    if (memo_slot_[static_cast<std::size_t>(i)] >= 0) continue;
    const Candidate& c = candidates[static_cast<std::size_t>(i)];
    points_.push_back({c.x, c.y});
    todo_.push_back(i);
  }
  if (todo_.empty()) return;
  const int count = static_cast<int>(todo_.size());
  m10_.resize(todo_.size());
  m01_.resize(todo_.size());
  angles_.resize(todo_.size());
  descriptors_.resize(todo_.size() * kDescriptorBytes);

  // Orientation on the raw level, descriptors on the blurred one (as ORB-SLAM2).
  kernels.ic_moments(level.pixels, points_.data(), count, m10_.data(), m01_.data());
  const auto angle = orientation_ == Orientation::opencv_fast ? orbslam_ic_angle_deg : ic_angle_deg;
  for (int i = 0; i < count; ++i)
    angles_[static_cast<std::size_t>(i)] =
        angle(m10_[static_cast<std::size_t>(i)], m01_[static_cast<std::size_t>(i)]);
  if (descriptor_ == DescriptorKind::box) {
    box_points_.resize(todo_.size());
    for (int i = 0; i < count; ++i) {
      const PixelPoint& p = points_[static_cast<std::size_t>(i)];
      box_points_[static_cast<std::size_t>(i)] = {static_cast<float>(p.x), static_cast<float>(p.y)};
    }
    if (selections_ == Selections::one) {
      box_describe_through_band(level, kernels, count);
    } else {
      if (!level_blurred()) blur_level(level, kernels);
      kernels.box_describe(integral_.view(), box_points_.data(), angles_.data(), count,
                           kBoxLevelScale, descriptors_.data());
    }
  } else if (selections_ == Selections::many) {
    if (!level_blurred()) blur_level(level, kernels);
    kernels.rbrief_describe(blurred_.view(), points_.data(), angles_.data(), count,
                            descriptors_.data());
  } else {
    describe_through_band(level, kernels, count);
  }
  for (int i = 0; i < count; ++i) {
    const std::size_t index = static_cast<std::size_t>(todo_[static_cast<std::size_t>(i)]);
    memo_slot_[index] = static_cast<std::int32_t>(memo_angle_deg_.size());
    memo_angle_deg_.push_back(angles_[static_cast<std::size_t>(i)]);
    Descriptor& descriptor = memo_descriptor_.emplace_back();
    std::memcpy(descriptor.data(),
                descriptors_.data() + static_cast<std::size_t>(i) * kDescriptorBytes,
                kDescriptorBytes);
  }
}

void LevelDescriptions::blur_level(const PyramidLevel& level, const KernelTable& kernels) {
  if (descriptor_ == DescriptorKind::box) {
    integral_.compute(level.pixels, kernels);
    blurred_end_ = level.geometry.height;
    return;
  }
  assert(selections_ == Selections::many);
  kernels.gaussian7_rows(level.pixels, blurred_.mutable_view(), 0, level.geometry.height, 0,
                         level.geometry.width);
  blurred_end_ = level.geometry.height;
}

void LevelDescriptions::describe_through_band(const PyramidLevel& level, const KernelTable& kernels,
                                              int count) {
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
                    kept_end, new_end, points_.data(), count, blur_columns_);
    blurred_top_ = new_top;
    blurred_end_ = new_end;
  };
  const auto describe = [&](int first, int last, int top) {
    for (int i = first; i < last; ++i) {
      const PixelPoint& p = points_[static_cast<std::size_t>(i)];
      shifted[static_cast<std::size_t>(i)] = {p.x, p.y - top};
    }
    kernels.rbrief_describe(
        {band.data, width, blurred_end_ - top, band.stride}, shifted.data() + first,
        angles_.data() + first, last - first,
        descriptors_.data() + static_cast<std::size_t>(first) * kDescriptorBytes);
  };
  describe_through_sliding_band(points_, count, kEdgeBorder, level.geometry.height,
                                blurred_.height(), make_rows, describe);
}

void LevelDescriptions::box_describe_through_band(const PyramidLevel& level,
                                                  const KernelTable& kernels, int count) {
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
                         angles_.data() + first, last - first, kBoxLevelScale,
                         descriptors_.data() + static_cast<std::size_t>(first) * kDescriptorBytes);
  };
  describe_through_sliding_band(points_, count, box_level_reach(), height + 1, integral_band_rows_,
                                make_rows, describe);
}

}  // namespace aief

#include "core/description/level_description.hpp"

#include "core/kernels/fast_atan2.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>

#include "core/kernels/ic_moments.hpp"
#include "core/description/patch_blur.hpp"

namespace aief {

namespace {

// Rows of keypoints one band of blurred rows serves at a time; the band adds kEdgeBorder rows
// above and below (every rBRIEF sample lies within kEdgeBorder of its keypoint).
constexpr int kBlurBandKeypointRows = 96;

}  // namespace

void LevelDescriptions::start(const LevelGeometry& geometry, Selections selections) {
  selections_ = selections;
  const int w = geometry.width, h = geometry.height;
  if (geometry.grid.count() > 0 && descriptor_ == DescriptorKind::rbrief) {
    // a level too small to use is never described
    if (selections_ == Selections::many)
      blurred_.resize(w, h);
    else
      blurred_.resize(w, std::min(h, kBlurBandKeypointRows + 2 * kEdgeBorder));
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
    if (!level_blurred()) blur_level(level, kernels);
    box_points_.resize(todo_.size());
    for (int i = 0; i < count; ++i) {
      const PixelPoint& p = points_[static_cast<std::size_t>(i)];
      box_points_[static_cast<std::size_t>(i)] = {static_cast<float>(p.x), static_cast<float>(p.y)};
    }
    kernels.box_describe(integral_.view(), box_points_.data(), angles_.data(), count,
                         kBoxLevelScale, descriptors_.data());
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
  // The points come in raster order, so the blurred rows they read, [y - kEdgeBorder, y +
  // kEdgeBorder], form a window sliding down the level. The band holds blurred rows [top, end);
  // when a point needs a row below it, the rows still needed move to the band's top and only
  // the new ones are blurred: every blurred row is computed once, in a buffer that stays in cache,
  // and only at the columns the points' patches cover (core/description/patch_blur.hpp).
  const std::vector<PixelPoint>& points = points_;
  std::vector<PixelPoint>& shifted = band_points_;
  shifted.resize(static_cast<std::size_t>(count));
  const int width = level.geometry.width, height = level.geometry.height;
  const int capacity = blurred_.height();
  const MutableImageView band = blurred_.mutable_view();
  int& top = blurred_top_;
  int& end = blurred_end_;
  top = end = 0;
  int first = 0;  // first point not yet described
  const auto describe_up_to = [&](int last) {
    if (last == first) return;
    for (int i = first; i < last; ++i) {
      const PixelPoint& p = points[static_cast<std::size_t>(i)];
      shifted[static_cast<std::size_t>(i)] = {p.x, p.y - top};
    }
    kernels.rbrief_describe(
        {band.data, width, end - top, band.stride}, shifted.data() + first, angles_.data() + first,
        last - first, descriptors_.data() + static_cast<std::size_t>(first) * kDescriptorBytes);
    first = last;
  };
  for (int i = 0; i < count; ++i) {
    const int y = points[static_cast<std::size_t>(i)].y;
    if (y + kEdgeBorder < end) continue;
    describe_up_to(i);
    const int new_top = y - kEdgeBorder;
    const int new_end = std::min(height, new_top + capacity);
    int kept_end = new_top;  // rows [new_top, kept_end) are already blurred in the band
    if (end > new_top) {
      std::memmove(band.data, band.row(new_top - top),
                   static_cast<std::size_t>(end - new_top) * static_cast<std::size_t>(band.stride));
      kept_end = end;
    }
    blur_patch_rows(kernels, level.pixels,
                    {band.row(kept_end - new_top), width, new_end - kept_end, band.stride},
                    kept_end, new_end, points.data(), count, blur_columns_);
    top = new_top;
    end = new_end;
  }
  describe_up_to(count);
}

}  // namespace aief

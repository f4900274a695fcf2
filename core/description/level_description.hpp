#pragma once
// Stage 4, second half, on one level: orientation (intensity centroid on the raw level) and
// descriptor of chosen candidates, memoised per candidate, so a candidate chosen again (the
// fallback, the sweep's thresholds) is described once. rBRIEF reads the blurred level, its rows
// held as the number of selections asks; the box descriptor the level's integral image
// (core/kernels/box_describe.hpp), held the same way.
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/distribution/candidate.hpp"
#include "core/kernels/integral_image.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

// How many times a frame's levels are selected, which decides how the blurred level is held.
enum class Selections {
  one,   // extract: the rows descriptors read are blurred into a small band sliding down the level
  many,  // the sweep: each level blurred whole once and kept, for every threshold's descriptors
};

class LevelDescriptions {
 public:
  // A new frame on a level of `geometry`: the memo emptied, the blurred rows sized.
  void start(const LevelGeometry& geometry, Selections selections);
  // Room in the memo for candidates [0, count) (after detection adds some).
  void track(std::size_t count) { memo_slot_.resize(count, -1); }
  // The angle formula of ExtractorOptions::orientation (for the frames that follow).
  void set_orientation(Orientation orientation) { orientation_ = orientation; }
  // The descriptor of ExtractorOptions::descriptor (for the frames that follow).
  void set_descriptor(DescriptorKind descriptor) { descriptor_ = descriptor; }

  // Describes the candidates `indices` (raster order) not described yet.
  void describe(const PyramidLevel& level, const std::vector<Candidate>& candidates,
                const std::vector<std::int32_t>& indices, const KernelTable& kernels);
  // Selections::many: whether the whole level is blurred yet (with the box descriptor: its
  // integral image made), and doing it (describe does it on its first call; a caller that spreads
  // the work, core/sweep/spread_sweep.hpp, does it first).
  bool level_blurred() const { return blurred_end_ > 0; }
  void blur_level(const PyramidLevel& level, const KernelTable& kernels);
  // Whether candidate i is described.
  bool described(std::int32_t i) const { return memo_slot_[static_cast<std::size_t>(i)] >= 0; }

  // Candidate i's orientation and descriptor (described).
  float angle_deg(std::int32_t i) const { return memo_angle_deg_[slot(i)]; }
  const Descriptor& descriptor(std::int32_t i) const { return memo_descriptor_[slot(i)]; }

 private:
  Orientation orientation_ = Orientation::atan2;
  DescriptorKind descriptor_ = DescriptorKind::rbrief;
  std::size_t slot(std::int32_t i) const;
  void describe_through_band(const PyramidLevel& level, const KernelTable& kernels, int count);
  void box_describe_through_band(const PyramidLevel& level, const KernelTable& kernels, int count);

  Selections selections_ = Selections::one;
  // Slot of each candidate (-1: not described yet) into dense arrays that hold only the
  // described ones, a few thousand among the 10^5 candidates of a large frame.
  std::vector<std::int32_t> memo_slot_;
  std::vector<float> memo_angle_deg_;
  std::vector<Descriptor> memo_descriptor_;
  // Blurred rows for rBRIEF: the whole level (Selections::many, made on first describe) or a
  // band of rows [blurred_top_, blurred_end_) that slides down as points are described.
  GrayImage blurred_;
  int blurred_top_ = 0, blurred_end_ = 0;
  // The box descriptor's integral image: of the whole level (Selections::many; blurred_end_ > 0
  // once made), or a band of integral_band_rows_ rows sliding down it (Selections::one).
  IntegralImage integral_;
  std::vector<std::uint32_t> integral_band_;
  int integral_band_rows_ = 0;
  std::vector<BoxPoint> box_points_;
  // One describe() call's buffers.
  std::vector<PixelPoint> points_, band_points_;
  std::vector<std::int32_t> todo_;
  std::vector<std::uint64_t> blur_columns_;
  std::vector<std::int32_t> m10_, m01_;
  std::vector<float> angles_;
  std::vector<std::uint8_t> descriptors_;
};

}  // namespace aief

#pragma once
// Stage 4, second half, on one level: orientation (intensity centroid on the raw level,
// core/description/keypoint_angles.hpp) and descriptor (the strategy ExtractorOptions::descriptor
// names, core/description/level_descriptor.hpp) of chosen candidates, memoised per candidate, so
// a candidate chosen again (the fallback, the sweep's thresholds) is described once.
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/options.hpp"
#include "core/description/keypoint_angles.hpp"
#include "core/description/level_descriptor.hpp"
#include "core/description/selections.hpp"
#include "core/distribution/candidate.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

class LevelDescriptions {
 public:
  // A new frame on a level of `geometry`: the memo emptied, the descriptor's input sized.
  void start(const LevelGeometry& geometry, Selections selections);
  // Room in the memo for candidates [0, count) (after detection adds some).
  void track(std::size_t count) { memo_slot_.resize(count, -1); }
  // The angle formula of ExtractorOptions::orientation (for the frames that follow).
  void set_orientation(Orientation orientation) { orientation_ = orientation; }
  // The descriptor of ExtractorOptions::descriptor (for the frames that follow; before start).
  void set_descriptor(DescriptorKind descriptor);

  // Describes the candidates `indices` (raster order) not described yet.
  void describe(const PyramidLevel& level, const std::vector<Candidate>& candidates,
                const std::vector<std::int32_t>& indices, const KernelTable& kernels);
  // Selections::many: whether the descriptor's input over the whole level (the blurred level,
  // the integral image) is made, and making it (describe makes it on its first call; a caller
  // that spreads the work, core/sweep/spread_sweep.hpp, makes it first).
  bool descriptor_input_ready() const;
  void prepare_descriptor_input(const PyramidLevel& level, const KernelTable& kernels);
  // Whether candidate i is described.
  bool described(std::int32_t i) const { return memo_slot_[static_cast<std::size_t>(i)] >= 0; }

  // Candidate i's orientation and descriptor (described).
  float angle_deg(std::int32_t i) const { return memo_angle_deg_[slot(i)]; }
  const Descriptor& descriptor(std::int32_t i) const { return memo_descriptor_[slot(i)]; }

 private:
  std::size_t slot(std::int32_t i) const;

  Orientation orientation_ = Orientation::atan2;
  LevelDescriptors descriptor_;
  // Slot of each candidate (-1: not described yet) into dense arrays that hold only the
  // described ones, a few thousand among the 10^5 candidates of a large frame.
  std::vector<std::int32_t> memo_slot_;
  std::vector<float> memo_angle_deg_;
  std::vector<Descriptor> memo_descriptor_;
  // One describe() call's buffers.
  KeypointAngles keypoint_angles_;
  std::vector<PixelPoint> points_;
  std::vector<std::int32_t> todo_;
  std::vector<float> angles_;
  std::vector<std::uint8_t> descriptors_;
};

}  // namespace aief

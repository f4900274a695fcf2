#pragma once
// rBRIEF (the learned ORB pattern, core/kernels/rbrief_describe.hpp) on the level blurred by the
// 7x7 Gaussian, as ORB-SLAM2 describes (docs/design.md §7). What it prepares: the blurred level,
// whole (Selections::many) or as a band of rows sliding down it, blurred only at the columns
// the points' patterns read (core/description/patch_blur.hpp). A LevelDescriptor
// (core/description/level_descriptor.hpp).
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/description/selections.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

class RbriefOnBlurredBand {
 public:
  static constexpr DescriptorKind kKind = DescriptorKind::rbrief;
  // Every sample lies within kEdgeBorder of its point (core/kernels/rbrief_describe.hpp).
  static int reach() { return kEdgeBorder; }

  void start(const LevelGeometry& geometry, Selections selections);
  bool whole_input_ready() const { return blurred_end_ > 0; }
  // The whole level blurred (Selections::many).
  void prepare_whole_input(const PyramidLevel& level, const KernelTable& kernels);
  void describe(const PyramidLevel& level, const KernelTable& kernels, const PixelPoint* points,
                const float* angles_deg, int count, std::uint8_t* descriptors);

 private:
  void describe_through_band(const PyramidLevel& level, const KernelTable& kernels,
                             const PixelPoint* points, const float* angles_deg, int count,
                             std::uint8_t* descriptors);

  Selections selections_ = Selections::one;
  // The whole level (Selections::many, blurred on first describe) or a band of rows
  // [blurred_top_, blurred_end_) that slides down as points are described.
  GrayImage blurred_;
  int blurred_top_ = 0, blurred_end_ = 0;
  std::vector<PixelPoint> band_points_;  // the points in the band's rows
  std::vector<std::uint64_t> blur_columns_;
};

}  // namespace aief

#pragma once
// The box descriptor (256 learned box-average tests, core/kernels/box_describe.hpp; docs/design.md
// "The box descriptor") on the level's integral image. What it prepares: the integral image,
// whole (Selections::many) or as a band of rows sliding down the level, summed from the band's
// own origin row (core/kernels/integral_image.hpp says why a band sums as the whole). A
// LevelDescriptor (core/description/level_descriptor.hpp).
#include <cstdint>
#include <vector>

#include "aief/features.hpp"
#include "aief/options.hpp"
#include "core/description/selections.hpp"
#include "core/kernels/box_describe.hpp"
#include "core/kernels/integral_image.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

class BoxOnIntegralBand {
 public:
  static constexpr DescriptorKind kKind = DescriptorKind::box;
  // Rows of the integral image around a keypoint on its own level (box_reach at kBoxLevelScale).
  static int reach();

  void start(const LevelGeometry& geometry, Selections selections);
  bool whole_input_ready() const { return integral_ready_; }
  // The whole level's integral image (Selections::many).
  void prepare_whole_input(const PyramidLevel& level, const KernelTable& kernels);
  void describe(const PyramidLevel& level, const KernelTable& kernels, const PixelPoint* points,
                const float* angles_deg, int count, std::uint8_t* descriptors);

 private:
  void describe_through_band(const PyramidLevel& level, const KernelTable& kernels,
                             const PixelPoint* points, const float* angles_deg, int count,
                             std::uint8_t* descriptors);

  Selections selections_ = Selections::one;
  // The whole level's integral image (Selections::many), or a band of integral_band_rows_ rows
  // sliding down it (Selections::one).
  IntegralImage integral_;
  bool integral_ready_ = false;
  std::vector<std::uint32_t> integral_band_;
  int integral_band_rows_ = 0;
  std::vector<BoxPoint> box_points_;  // the points, as the box kernel takes them
};

}  // namespace aief

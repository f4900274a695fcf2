#pragma once
// The descriptor as a strategy: what ExtractorOptions::descriptor names, seen by the code that
// describes a level's keypoints (core/description/level_description.hpp for extraction,
// core/frame/given_keypoints.hpp for Extractor::describe). Each descriptor is one type with the
// members LevelDescriptor asks for; LevelDescriptors lists them, one row each, and the one of a
// frame is chosen once per level (std::visit per describe call, never a call per keypoint).
// Adding one: CONTRIBUTING.md, "Adding a descriptor".
#include <concepts>
#include <cstdint>
#include <variant>

#include "aief/options.hpp"
#include "core/description/box_on_integral_band.hpp"
#include "core/description/rbrief_on_blurred_band.hpp"
#include "core/description/selections.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"
#include "core/level/pyramid_level.hpp"

namespace aief {

// What a descriptor is on one level:
//   kKind                 its DescriptorKind
//   reach()               rows above and below a keypoint its describe reads on the level (the
//                         band it holds is sized by it)
//   start(geometry, s)    a new frame on a level of that geometry: its input's rows sized for
//                         Selections s, nothing prepared yet
//   whole_input_ready()   Selections::many: whether its input over the whole level is made
//   prepare_whole_input   Selections::many: makes it (describe makes it when missing; a caller
//                         that spreads the work, core/sweep/spread_sweep.hpp, makes it first)
//   describe              32 bytes per point (kDescriptorBytes) at points in raster order (y
//                         ascending), each at least kEdgeBorder from the level's edges, with
//                         their angles in degrees; Selections::one prepares its input in a band
//                         sliding down the level, Selections::many reads the whole level's
template <class D>
concept LevelDescriptor = requires(D descriptor, const D& held, const LevelGeometry& geometry,
                                   Selections selections, const PyramidLevel& level,
                                   const KernelTable& kernels, const PixelPoint* points,
                                   const float* angles_deg, int count, std::uint8_t* descriptors) {
  { D::kKind } -> std::convertible_to<DescriptorKind>;
  { D::reach() } -> std::same_as<int>;
  descriptor.start(geometry, selections);
  { held.whole_input_ready() } -> std::same_as<bool>;
  descriptor.prepare_whole_input(level, kernels);
  descriptor.describe(level, kernels, points, angles_deg, count, descriptors);
};

// Every descriptor, a row each, in DescriptorKind's order.
using LevelDescriptors = std::variant<RbriefOnBlurredBand,  //
                                      BoxOnIntegralBand>;

// The descriptor of `kind` (state emptied).
LevelDescriptors level_descriptor_of(DescriptorKind kind);
// Its kind.
DescriptorKind kind_of(const LevelDescriptors& descriptor);

}  // namespace aief

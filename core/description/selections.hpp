#pragma once
// How many times a frame's levels are selected, which decides how a descriptor's input (the
// blurred level, the integral image: core/description/level_descriptor.hpp) is held.
namespace aief {

enum class Selections {
  one,   // extract: the rows descriptors read are made in a small band sliding down the level
  many,  // the sweep: each level's input made whole once and kept, for every threshold's
         // descriptors
};

}  // namespace aief

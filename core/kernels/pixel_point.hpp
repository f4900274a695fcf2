#pragma once
#include <cstdint>

namespace aief {

// Integer pixel position inside one pyramid level.
struct PixelPoint {
  std::int32_t x = 0;
  std::int32_t y = 0;
};

}  // namespace aief

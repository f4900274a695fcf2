#include "core/level/keypoint_position.hpp"

#include <cmath>

namespace aief {

float parabola_peak_offset(int before, int peak, int after) {
  const int curvature = before - 2 * peak + after;  // < 0 at a strict maximum
  if (peak <= before || peak <= after) return 0.0f;
  return 0.5f * static_cast<float>(before - after) / static_cast<float>(curvature);
}

LevelToImage level_to_image(CoordinateMap map, bool subpixel, float scale, int width0, int height0,
                            int width_n, int height_n) {
  LevelToImage mapping;
  mapping.map = map;
  mapping.scale = scale;
  mapping.ratio_x = static_cast<double>(width0) / static_cast<double>(width_n);
  mapping.ratio_y = static_cast<double>(height0) / static_cast<double>(height_n);
  mapping.subpixel = subpixel;
  return mapping;
}

ImagePoint keypoint_position(const Candidate& c, const LevelToImage& mapping) {
  float dx = 0.0f, dy = 0.0f;
  if (mapping.subpixel) {
    dx = parabola_peak_offset(c.score_left, c.score, c.score_right);
    dy = parabola_peak_offset(c.score_up, c.score, c.score_down);
  }
  if (mapping.map == CoordinateMap::scaled)
    return {(static_cast<float>(c.x) + dx) * mapping.scale,
            (static_cast<float>(c.y) + dy) * mapping.scale};
  return {static_cast<float>((c.x + 0.5 + dx) * mapping.ratio_x - 0.5),
          static_cast<float>((c.y + 0.5 + dy) * mapping.ratio_y - 0.5)};
}

PixelPoint level_pixel(ImagePoint position, const LevelToImage& mapping) {
  // Doubles out of range of int (a huge or non-finite position) land outside every level.
  const auto nearest = [](double v) {
    return std::isfinite(v) && std::abs(v) < 1e9 ? static_cast<std::int32_t>(std::nearbyint(v))
                                                 : -1;
  };
  if (mapping.map == CoordinateMap::scaled)
    return {nearest(static_cast<double>(position.x / mapping.scale)),
            nearest(static_cast<double>(position.y / mapping.scale))};
  return {nearest((position.x + 0.5) / mapping.ratio_x - 0.5),
          nearest((position.y + 0.5) / mapping.ratio_y - 0.5)};
}

}  // namespace aief

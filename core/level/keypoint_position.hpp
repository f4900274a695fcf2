#pragma once
// Where a level's candidate lands in level-0 pixels (docs/design.md §8).
//
// The pyramid resamples pixel-centre aligned (core/kernels/resize_bilinear_rows.hpp: level pixel x
// samples level n - 1 at (x + 0.5) * W_{n-1} / W_n - 0.5), and those maps compose exactly, so level
// pixel x of level n sits at (x + 0.5) * (W_0 / W_n) - 0.5 in level 0, per axis with the
// level's real size ratio. The paper and ORB-SLAM2 use x * scale_factor^n instead, which is off
// by about (scale - 1) / 2 pixels plus the rounding of the level size: 3-8 px at levels 6-7.
//
// Sub-pixel refinement: a parabola through the FAST scores at x - 1, x, x + 1 (and likewise in
// y) peaks at x + (s(x-1) - s(x+1)) / (2 (s(x-1) - 2 s(x) + s(x+1))). A candidate is a strict
// local maximum, so the offset lies in (-0.5, 0.5). Computed here, in plain scalar float code
// built with -ffp-contract=off, from integer scores that every kernel set gives alike: the same
// bits in every build.
#include "aief/options.hpp"
#include "core/distribution/candidate.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

// The peak offset of the parabola through (-1, before), (0, peak), (1, after); 0 when peak is not
// above both (a flat or one-sided neighbourhood has no interior peak).
float parabola_peak_offset(int before, int peak, int after);

// How one level maps to level 0.
struct LevelToImage {
  CoordinateMap map = CoordinateMap::scaled;
  float scale = 1;     // scale_factor^n in float (ORB-SLAM2), for CoordinateMap::scaled
  double ratio_x = 1;  // W_0 / W_n, for CoordinateMap::pixel_centre
  double ratio_y = 1;  // H_0 / H_n
  bool subpixel = false;
};

LevelToImage level_to_image(CoordinateMap map, bool subpixel, float scale, int width0, int height0,
                            int width_n, int height_n);

struct ImagePoint {
  float x, y;
};

// The candidate's position in level-0 pixels.
ImagePoint keypoint_position(const Candidate& candidate, const LevelToImage& mapping);

// The level pixel nearest to a level-0 position: the map above inverted and rounded half to even
// (cvRound, as cv::ORB places a given keypoint on its level). A detected keypoint's sub-pixel
// offset lies in (-0.5, 0.5), so this gives back the pixel it was detected at.
PixelPoint level_pixel(ImagePoint position, const LevelToImage& mapping);

}  // namespace aief

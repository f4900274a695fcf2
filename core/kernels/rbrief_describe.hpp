#pragma once
// rBRIEF-256 over the blurred level with the learned ORB pattern (data/orb_pattern_31.txt,
// compiled in), as ORB-SLAM2 and OpenCV compute it (docs/design.md §7):
//   a = (float)cos(angle), b = (float)sin(angle), angle = angle_deg * (float)(pi / 180)
//   offset of pattern point (px, py):  dx = lrint(px * a - py * b), dy = lrint(px * b + py * a)
//   (float arithmetic, no contraction, round half to even, as cvRound)
//   test i = I(p_i) < I(q_i) goes to bit i % 8 (LSB first) of byte i / 8.
#include <cstdint>

#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

// Where the rotated samples can lie, whatever the angle: every pattern point is within 18.39 of
// the keypoint (the largest, (13, 13)), so a rotated sample's rounded offsets satisfy
// |dx|, |dy| <= kSampleReach, and one whose |dy| rounds to d came from a true |dy| >= d - 0.5,
// so its |dx| <= sqrt(18.39^2 - (d - 0.5)^2) rounded up to the next half:
//   kSampleHalfWidth[d] = floor(sqrt(18.39^2 - max(0, d - 0.5)^2) + 0.5).
// A disc of 1125 pixels where the square is 1369: core/description/patch_blur.cpp blurs only these
// columns. Rbrief.RotatedSamplesStayInsideTheirDisc checks it from the pattern at 36000 angles.
inline constexpr int kSampleReach = 18;
inline constexpr int kSampleHalfWidth[kSampleReach + 1] = {18, 18, 18, 18, 18, 18, 18, 17, 17, 16,
                                                           16, 15, 14, 13, 12, 11, 10, 8,  6};

// The 256 pairs (x1, y1, x2, y2) of the learned pattern, in file order.
const std::int8_t (*orb_pattern_31())[4];

// Writes 32 bytes per point to descriptors (n * 32). Points lie >= kEdgeBorder from every edge
// of `blurred`, so every rotated sample (at most 18 from its point in x and y) is inside it.
void rbrief_describe_scalar(ImageView blurred, const PixelPoint* points, const float* angle_deg,
                            int n, std::uint8_t* descriptors);

}  // namespace aief

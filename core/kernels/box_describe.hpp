#pragma once
// The box descriptor: 256 learned box-average tests (TEBLID's form, docs/design.md "The box
// descriptor"), read from an integral image (core/kernels/integral_image.hpp); the table is
// data/box_descriptor/<AIEF_BOX_TABLE>.txt, compiled in (default teblid_256).
//
// Test i of the table, BoxTest {x1, y1, x2, y2, radius, threshold_hundredths}, on a keypoint at
// (x, y) of the integral image's pixels (floats: pixel centres at integers) with angle angle_deg,
// at `scale` (patch pixels to image pixels: keypoint size / 32, i.e. kPatchSize / 32 on the
// keypoint's own level), in this exact float arithmetic (no contraction: -ffp-contract=off):
//   t = angle_deg * (float)(pi / 180), a = scale * (float)cos(t), b = scale * (float)sin(t)
//   box centre (cx, cy) of patch point (px, py):
//       cx = nearbyint(x + (px * a - py * b)),  cy = nearbyint(y + (px * b + py * a))
//     (round half to even); the radius R = nearbyint(scale * radius), the same for every keypoint
//     of a call;
//   the box covers columns [cx - R, cx + R] and rows [cy - R, cy + R], clipped to the image as
//   OpenCV's BEBLID does at the border: in integral coordinates x0 = clamp(cx - R, 0, W - 1),
//   x1 = clamp(cx + R + 1, 1, W) (rows alike), so it is never empty; its sum S and area A follow;
//   bit i = 1 iff mean 1 - mean 2 <= threshold, exactly, in integers:
//       100 * S1 * A2 - 100 * S2 * A1 <= threshold_hundredths * A1 * A2   (int64)
//   and goes to bit i % 8 (LSB first) of byte i / 8, as rBRIEF (OpenCV's TEBLID writes bit i to
//   bit 7 - i % 8: the same tests, each byte's bits reversed).
// Inside the image (every box unclipped, A1 = A2 = A) the test is S1 - S2 <= floor(threshold *
// A / 100): the vector kernels take that path and the scalar reference's for a clipped keypoint.
#include <cstdint>

#include "core/kernels/integral_image.hpp"

namespace aief {

// One test of the table (data/box_descriptor/README.md): box centres in patch pixels, origin at
// the patch centre, the radius of both boxes, the threshold on mean gray levels in hundredths.
struct BoxTest {
  std::int8_t x1, y1, x2, y2, radius;
  std::int32_t threshold_hundredths;
};

inline constexpr int kBoxTests = 256;
// The side of the patch the tests were learned on: a keypoint of size S maps it at scale S / 32.
inline constexpr int kBoxPatchSide = 32;

// The scale on a keypoint's own level: a keypoint there has size kPatchSize (31), so the 32-pixel
// patch the tests were learned on maps at 31 / 32 (TEBLID's scale factor 1, which its authors give
// for ORB keypoints); every radius of the TEBLID table stays as it is (nearbyint(r * 31 / 32) = r).
inline constexpr float kBoxLevelScale = 31.0f / kBoxPatchSide;

// The compiled-in table, kBoxTests tests in bit order, and its name ("teblid_256").
const BoxTest* box_table();
const char* box_table_name();

// A keypoint's position in the integral image's pixels.
struct BoxPoint {
  float x = 0;
  float y = 0;
};

// How far from a keypoint at integer (x, y) a describe at `scale` reads: every entry of every box
// lies in rows (and columns) [y - reach, y + reach] of the integral image, clipped to it.
int box_reach(float scale);

// Writes 32 bytes per point to descriptors (n * 32), as the contract above says. Any position
// (boxes are clipped to the image); the image is at least 1 x 1; 0 < scale <= 4. A band of the
// integral's rows (IntegralView::first_row) serves points at integer positions whose reach it
// holds.
void box_describe_scalar(IntegralView integral, const BoxPoint* points, const float* angle_deg,
                         int n, float scale, std::uint8_t* descriptors);

}  // namespace aief

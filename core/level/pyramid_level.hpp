#pragma once
// One pyramid level's pixels: its geometry, how it is made from the level above, and the pixels.
#include "aief/image.hpp"
#include "core/kernels/resize_bilinear_rows.hpp"
#include "core/kernels/resize_opencv_linear_rows.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

struct PyramidLevel {
  LevelGeometry geometry;
  ResizePlan resize_plan;  // from the previous level (empty for level 0)
  ImageView pixels;        // the level: the caller's image for level 0, else `image`
  GrayImage image;         // pixels of levels >= 1 (unused for level 0)
  // With PyramidResampling::opencv the pixels' plan (the detection mask keeps resize_plan).
  OpenCvResizePlan opencv_plan;
  // The detection mask at this level, 255 where keypoints may be and 0 elsewhere; 0 x 0 without
  // a mask (core/level/caller_mask.hpp).
  GrayImage detection_mask;
  // What FAST reads: `pixels`, or with ExtractorOptions::low_entropy_sharpen `sharpened` once
  // stage 2 made it (core/entropy/low_entropy_sharpen.hpp). Orientation and descriptors read
  // `pixels`. With ExtractorOptions::detection_smoothing, `smoothed` (of `pixels` or `sharpened`).
  ImageView detection_pixels;
  GrayImage sharpened;
  GrayImage smoothed;

  bool has_detection_mask() const { return detection_mask.width() > 0; }

  // Whether the level can hold keypoints (and is built): both sides >= 2 * kEdgeBorder + 1.
  bool usable() const { return geometry.grid.count() > 0; }
};

}  // namespace aief

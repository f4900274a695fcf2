#pragma once
// Descriptors of keypoints the caller gives (cv::Feature2D::compute; docs/opencv.md), computed
// exactly as for detected ones, so describing the keypoints an extraction returned gives back its
// bytes:
//   level        the keypoint's octave, as cv::ORB takes it (its size is not read); an octave
//                outside [0, n_levels) is an error
//   level pixel  the level-0 position mapped back to the level and rounded (level_pixel in
//                core/level/keypoint_position.hpp)
//   border rule  a keypoint whose level pixel lies closer than kEdgeBorder to its level's edge
//                is removed, as cv::ORB removes given keypoints within its edge threshold of the
//                image: the area left is exactly the one detected keypoints come from, where the
//                whole rBRIEF pattern lies inside the level (no padding, no reflected samples).
//                A level too small to hold a keypoint removes all of its keypoints.
//   orientation  GivenAngles::recompute (the default): the intensity centroid on the raw level,
//                as for detected keypoints, replaces the given angle. GivenAngles::keep: the given
//                angle is used as it is, as cv::ORB::compute does: any finite number of degrees
//                (OpenCV's "no angle", -1, too: the pattern is rotated by cos and sin of it).
//   descriptor   the one ExtractorOptions::descriptor names, by the strategy detected keypoints
//                are described with (core/description/level_descriptor.hpp), on the level's
//                keypoints in raster order
#include <cstdint>
#include <string>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "core/description/keypoint_angles.hpp"
#include "core/description/level_descriptor.hpp"
#include "core/frame/frame_analysis.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

// Storage reused from call to call.
struct GivenKeypointScratch {
  // Per level: indices of its kept keypoints, in raster order of their level pixels.
  std::vector<std::vector<std::int32_t>> level_members;
  std::vector<PixelPoint> level_pixel;       // per keypoint
  std::vector<PixelPoint> points;            // one level's, in level_members order
  KeypointAngles keypoint_angles;            // GivenAngles::recompute
  std::vector<float> level_angle_deg;        // one level's
  std::vector<float> angle_deg;              // per keypoint
  std::vector<std::int32_t> descriptor_row;  // per keypoint: its row (-1: removed)
  std::vector<std::uint8_t> descriptors;     // 32 bytes a row, level by level
  LevelDescriptors descriptor;               // the options' (its input's band)
};

// Why `octave`, a number as the caller gave it (before it narrows to int: Python's floats and
// 64-bit integers), names no level of a pyramid of `n_levels`: "not an integer level" or
// "beyond the pyramid's levels 0..7"; "" when it names one.
std::string octave_fault(double octave, int n_levels);

// Throws aief::Error, naming the keypoint, when its octave is outside [0, n_levels) or, with
// GivenAngles::keep, its angle is not finite.
void check_given_keypoints(const std::vector<Keypoint>& keypoints, int n_levels,
                           GivenAngles angles);

// `analysis` has been started on the image (FrameAnalysis::start); this builds the levels the
// keypoints need. out.keypoints := the kept keypoints in their given order, each with its angle
// recomputed and every other field as given; out.descriptors := theirs. kept_indices (when
// given) := the index in `keypoints` of each kept one.
void describe_given_keypoints(FrameAnalysis& analysis, const KernelTable& kernels,
                              const std::vector<Keypoint>& keypoints, GivenAngles angles,
                              GivenKeypointScratch& scratch, Features& out,
                              std::vector<std::int32_t>* kept_indices);

}  // namespace aief

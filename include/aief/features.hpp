#pragma once
// What an extraction returns: keypoints in level-0 pixels and their 32-byte descriptors (rBRIEF,
// or the box descriptor: Features::descriptor says which).
#include <array>
#include <cstdint>
#include <vector>

#include "aief/options.hpp"

namespace aief {

struct Keypoint {
  // Level-0 pixels: (level x + 0.5) * (W_0 / W_octave) - 0.5 plus the sub-pixel offset by default,
  // level x times scale_factor^octave in the aief-paper and orbslam2 modes
  // (ExtractorOptions::coordinates).
  float x = 0;
  float y = 0;
  float size = 0;       // kPatchSize * scale_factor^octave
  float angle_deg = 0;  // intensity-centroid orientation, [0, 360)
  float response = 0;   // FAST corner score (OpenCV's definition)
  int octave = 0;       // pyramid level
};

// Where the angle of a given keypoint comes from (Extractor::describe, aief/extractor.hpp).
enum class GivenAngles {
  recompute,  // the intensity centroid, as for detected keypoints (describe gives extract's bytes)
  keep,       // the given angle (any finite number of degrees), as cv::ORB::compute keeps it
};

using Descriptor = std::array<std::uint8_t, kDescriptorBytes>;

// How the entropy mask went for this image.
struct ExtractionInfo {
  double entropy_threshold_requested = 0;  // F asked for
  double entropy_threshold_used = 0;       // F applied (lower when the mask would starve)
  bool threshold_lowered = false;          // true when used < requested
  double image_entropy_bits = 0;           // entropy of level 0 (Eq. 7), same measure
  int blocks_total = 0;                    // blocks over all levels
  int blocks_kept = 0;                     // blocks with entropy > F used
  // --entropy-threshold auto: Otsu's effectiveness eta of the frame's block entropies, in [0, 1]
  // (how well one F splits them into two classes; below 0.75 the aief mode takes F = 0). 0
  // otherwise.
  double auto_threshold_effectiveness = 0;
};

struct Features {
  int image_width = 0;
  int image_height = 0;
  std::vector<Keypoint> keypoints;  // octave ascending, then level y, then level x (integer pixels)
  std::vector<Descriptor> descriptors;  // descriptors[i] describes keypoints[i]
  // Which descriptor `descriptors` holds (ExtractorOptions::descriptor): rBRIEF and box
  // descriptors never match each other (require_same_descriptor, aief/match.hpp).
  DescriptorKind descriptor = DescriptorKind::rbrief;
  ExtractionInfo info;
};

}  // namespace aief

#pragma once
// A drop-in for ORB-SLAM3's ORBextractor (target aief::opencv): the same constructor, call
// operator (with the lapping area of stereo fisheye rigs and its returned count) and accessors,
// configured from the same settings keys, computing AIEF features (docs/orbslam3.md shows the
// swap). Constructors, accessors, mvImagePyramid and the settings keys are
// OrbSlamExtractorBase's, shared with the ORB-SLAM2 drop-in.
#include <vector>

#include <opencv2/core.hpp>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/orbslam_extractor_base.hpp"

namespace aief::orbslam3 {

// Its mode unless the settings name one (kDefaultMode): faithful, ORB-SLAM3's own keypoints and
// descriptors to the bit on aief's kernels (docs/slam.md, "The faithful mode"), measured inside
// ORB-SLAM3 on three seeds and seven families ("What you get by swapping the extractor"); no
// entropy-guided variant met the targets set for a new default there. Monocular settings keep
// the engine's keypoint convention.
class ORBextractor : public OrbSlamExtractorWithDefault<Mode::faithful> {
 public:
  // ORB-SLAM's constructor and the settings reader with this mode (OrbSlamExtractorWithDefault).
  using OrbSlamExtractorWithDefault::OrbSlamExtractorWithDefault;
  static ORBextractor from_settings(const cv::FileStorage& settings);

  // As ORB-SLAM3's: a keypoint whose x (level-0 pixels) lies in [vLappingArea[0],
  // vLappingArea[1]] (bounds included, compared as float) is written at the end of the arrays,
  // the first such keypoint last; the others fill the front in the engine's order. Returns how
  // many are at the front (ORB-SLAM3's monoIndex): all of them when no keypoint is in the area.
  // Descriptor row i belongs to keypoint i: N x 32 CV_8U, released when there is no keypoint.
  // The mask is ignored, as in ORB-SLAM3. An empty image returns -1 and leaves the outputs as
  // they are, as ORB-SLAM3 does. Image CV_8UC1 (CV_8UC3/4 converted to gray); mvImagePyramid
  // is refreshed. Throws aief::Error for another type, an image smaller than
  // 2 * kEdgeBorder + 1 pixels in a side, or fewer than two lapping bounds (ORB-SLAM3 would
  // read past the vector).
  int operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                 cv::OutputArray descriptors, std::vector<int>& vLappingArea);
};

}  // namespace aief::orbslam3

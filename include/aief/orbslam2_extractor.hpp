#pragma once
// A drop-in for ORB-SLAM2's ORBextractor (target aief::opencv): the same constructor, call
// operator and accessors, configured from the same settings keys, computing AIEF features
// (docs/orbslam2.md shows the swap). Constructors, accessors, mvImagePyramid and the settings
// keys are OrbSlamExtractorBase's, shared with the ORB-SLAM3 drop-in.
#include <vector>

#include <opencv2/core.hpp>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/orbslam_extractor_base.hpp"

namespace aief {

// Its mode unless the settings name one (kDefaultMode): orbslam2, ORB-SLAM's choices on aief's
// kernels (docs/slam.md, "Which choice costs what"). Not faithful: that mode reproduces ORB-SLAM3's
// extractor, whose cells (35 pixels) are not ORB-SLAM2's (30).
class ORBextractor : public OrbSlamExtractorWithDefault<Mode::orbslam2> {
 public:
  // ORB-SLAM's constructor and the settings reader with this mode (OrbSlamExtractorWithDefault).
  using OrbSlamExtractorWithDefault::OrbSlamExtractorWithDefault;
  static ORBextractor from_settings(const cv::FileStorage& settings);

  // As ORB-SLAM2: image CV_8UC1 (CV_8UC3/4 converted to gray); the mask is ignored, as in
  // ORB-SLAM2; descriptors become an N x 32 CV_8U matrix, released when there is no keypoint
  // (as ORB-SLAM2). mvImagePyramid is refreshed. Throws aief::Error for an empty image, another
  // type, or one smaller than 2 * kEdgeBorder + 1 pixels in a side.
  void operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                  cv::OutputArray descriptors);
};

}  // namespace aief

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

class ORBextractor : public OrbSlamExtractorBase {
 public:
  // The mode unless the settings name one: orbslam2, ORB-SLAM's choices on aief's kernels
  // (docs/slam.md, "Which choice costs what"). Not faithful: that mode reproduces ORB-SLAM3's
  // extractor, whose cells (35 pixels) are not ORB-SLAM2's (30).
  static constexpr Mode kDefaultMode = Mode::orbslam2;

  // As ORB-SLAM2, the other options kDefaultMode's.
  ORBextractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST)
      : OrbSlamExtractorBase(nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST, kDefaultMode) {}
  explicit ORBextractor(const ExtractorOptions& options) : OrbSlamExtractorBase(options) {}

  // The options from a settings file as ORB-SLAM2 reads it, plus our keys
  // (OrbSlamExtractorBase::options_from_settings, with kDefaultMode).
  static ExtractorOptions options_from_settings(const cv::FileStorage& settings) {
    return OrbSlamExtractorBase::options_from_settings(settings, kDefaultMode);
  }
  static ORBextractor from_settings(const cv::FileStorage& settings);

  // As ORB-SLAM2: image CV_8UC1 (CV_8UC3/4 converted to gray); the mask is ignored, as in
  // ORB-SLAM2; descriptors become an N x 32 CV_8U matrix, released when there is no keypoint
  // (as ORB-SLAM2). mvImagePyramid is refreshed. Throws aief::Error for an empty image, another
  // type, or one smaller than 2 * kEdgeBorder + 1 pixels in a side.
  void operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                  cv::OutputArray descriptors);
};

}  // namespace aief

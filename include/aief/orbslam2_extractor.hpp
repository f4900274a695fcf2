#pragma once
// A drop-in for ORB-SLAM2's ORBextractor (target aief::opencv): the same constructor, call
// operator and accessors, configured from the same settings keys, computing AIEF features
// (docs/orbslam2.md shows the swap).
#include <vector>

#include <opencv2/core.hpp>

#include "aief/extractor.hpp"

namespace aief {

class ORBextractor {
 public:
  // ORB-SLAM2's signature; the rest of the options are ExtractorOptions defaults (AIEF mode).
  ORBextractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST);
  explicit ORBextractor(const ExtractorOptions& options);

  // From a settings file as ORB-SLAM2 reads it: ORBextractor.nFeatures, .scaleFactor, .nLevels,
  // .iniThFAST, .minThFAST, and ours: ORBextractor.mode (aief | orbslam2 | quadtree-entropy),
  // ORBextractor.entropyThreshold (a number, or "auto"), ORBextractor.blockSize. Missing keys
  // keep ExtractorOptions' defaults; a value of the wrong kind (text for a number, 1.5 for an
  // integer, an unknown mode) throws aief::Error naming the key, out-of-range values throw from
  // ExtractorOptions::validate. scaleFactor is rounded to float, as ORB-SLAM2's Tracking reads
  // it, so from_settings and the five-number constructor give the same extractor.
  static ORBextractor from_settings(const cv::FileStorage& settings);
  // The options alone, e.g. to double nFeatures for the monocular initialiser (docs/orbslam2.md).
  static ExtractorOptions options_from_settings(const cv::FileStorage& settings);

  // As ORB-SLAM2: image CV_8UC1 (CV_8UC3/4 converted to gray); the mask is ignored, as in
  // ORB-SLAM2; descriptors become an N x 32 CV_8U matrix, released when there is no keypoint
  // (as ORB-SLAM2). mvImagePyramid is refreshed. Throws aief::Error for an empty image, another
  // type, or one smaller than 2 * kEdgeBorder + 1 pixels in a side.
  void operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                  cv::OutputArray descriptors);

  int GetLevels() const { return nlevels; }
  float GetScaleFactor() const { return scaleFactor; }
  std::vector<float> GetScaleFactors() const { return mvScaleFactor; }
  std::vector<float> GetInverseScaleFactors() const { return mvInvScaleFactor; }
  std::vector<float> GetScaleSigmaSquares() const { return mvLevelSigma2; }
  std::vector<float> GetInverseScaleSigmaSquares() const { return mvInvLevelSigma2; }

  // The levels of the last frame (headers over the extractor's buffers: valid until the next
  // call), as ORB-SLAM2's stereo matching reads them. Levels too small to build are empty.
  std::vector<cv::Mat> mvImagePyramid;

  const Extractor& extractor() const { return extractor_; }

 private:
  void compute_scales();

  Extractor extractor_;
  Features features_;
  cv::Mat gray_;
  int nlevels;
  float scaleFactor;
  std::vector<float> mvScaleFactor, mvInvScaleFactor, mvLevelSigma2, mvInvLevelSigma2;
};

}  // namespace aief

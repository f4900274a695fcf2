#pragma once
// What the ORB-SLAM2 and ORB-SLAM3 drop-ins share (target aief::opencv): ORBextractor's
// constructor, scale accessors and mvImagePyramid, which the two versions have in common, and
// the settings keys both read. Each drop-in adds its own call operator:
// aief::ORBextractor (aief/orbslam2_extractor.hpp) and aief::orbslam3::ORBextractor
// (aief/orbslam3_extractor.hpp).
#include <vector>

#include <opencv2/core.hpp>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/extractor.hpp"

namespace aief {

class OrbSlamExtractorBase {
 public:
  // ORB-SLAM's signature; the rest of the options are `mode`'s (each drop-in passes its own
  // default: ORB-SLAM's choices on aief's kernels, docs/slam.md).
  OrbSlamExtractorBase(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST,
                       Mode mode = Mode::orbslam2);
  explicit OrbSlamExtractorBase(const ExtractorOptions& options);

  // The options from a settings file as ORB-SLAM2 and ORB-SLAM3 read it: ORBextractor.nFeatures,
  // .scaleFactor, .nLevels, .iniThFAST, .minThFAST, and ours: every extractor option has a key
  // (ORBextractor.mode, .entropyThreshold (a number or "auto"), .blockSize, .threads, ...; the
  // list is the option table's, core/options/extractor_option_rows.cpp, and `aief extract --help`
  // explains each). The mode is `default_mode` (each drop-in's own) unless ORBextractor.mode names
  // another (the AIEF keys, such as .entropyThreshold, need ORBextractor.mode: "aief"). Keypoints
  // sit at ORB-SLAM's integer level pixels when the settings describe a stereo rig or a depth
  // camera (Camera.bf, Stereo.b, Camera2.fx, RGBD.DepthMapFactor, ...: Frame::ComputeStereoMatches
  // needs them), else at the engine's pixel-centre, sub-pixel positions (docs/orbslam2.md,
  // "Differences to know"). Missing keys keep the mode's values; a wrong value throws aief::Error
  // naming the key and what it accepts; a mode's conflicts are refused as in the CLI. scaleFactor
  // is rounded to float, as both versions' Tracking reads it, so settings and the five-number
  // constructor give the same extractor. Also the way to change nFeatures for the monocular
  // initialiser.
  static ExtractorOptions options_from_settings(const cv::FileStorage& settings,
                                                Mode default_mode = Mode::orbslam2);

  // The tables of ORB-SLAM's constructor (both versions): scale_n = scale_(n-1) * scaleFactor
  // in float, sigma2_n = scale_n^2, and their float inverses.
  int GetLevels() const { return nlevels; }
  float GetScaleFactor() const { return scaleFactor; }
  std::vector<float> GetScaleFactors() const { return mvScaleFactor; }
  std::vector<float> GetInverseScaleFactors() const { return mvInvScaleFactor; }
  std::vector<float> GetScaleSigmaSquares() const { return mvLevelSigma2; }
  std::vector<float> GetInverseScaleSigmaSquares() const { return mvInvLevelSigma2; }

  // The levels of the last frame (headers over the extractor's buffers: valid until the next
  // call), as ORB-SLAM's stereo matching reads them. Levels too small to build are empty.
  std::vector<cv::Mat> mvImagePyramid;

  const Extractor& extractor() const { return extractor_; }
  // How the entropy mask went on the last frame: the F it requested (the carried F: docs/design.md
  // §10), the F used, the blocks kept.
  const ExtractionInfo& last_frame_info() const { return features_.info; }

 protected:
  // The features of one frame, as both call operators start: image CV_8UC1 (CV_8UC3/4 converted
  // to gray), mvImagePyramid refreshed. The result is valid until the next call. Throws
  // aief::Error for an empty image, another type, or one smaller than 2 * kEdgeBorder + 1
  // pixels in a side.
  const Features& extract_frame(cv::InputArray image);

 private:
  void compute_scales();

  Extractor extractor_;
  Features features_;
  cv::Mat gray_;
  int nlevels;
  float scaleFactor;
  std::vector<float> mvScaleFactor, mvInvScaleFactor, mvLevelSigma2, mvInvLevelSigma2;
};

// What the two drop-ins share word for word: ORB-SLAM's five-number constructor and the settings
// reader, each with the drop-in's own default mode (its kDefaultMode).
template <Mode DefaultMode>
class OrbSlamExtractorWithDefault : public OrbSlamExtractorBase {
 public:
  static constexpr Mode kDefaultMode = DefaultMode;

  // As ORB-SLAM, the other options kDefaultMode's.
  OrbSlamExtractorWithDefault(int nfeatures, float scaleFactor, int nlevels, int iniThFAST,
                              int minThFAST)
      : OrbSlamExtractorBase(nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST, kDefaultMode) {}
  explicit OrbSlamExtractorWithDefault(const ExtractorOptions& options)
      : OrbSlamExtractorBase(options) {}

  // The options from a settings file as ORB-SLAM reads it, plus our keys
  // (OrbSlamExtractorBase::options_from_settings, with kDefaultMode).
  static ExtractorOptions options_from_settings(const cv::FileStorage& settings) {
    return OrbSlamExtractorBase::options_from_settings(settings, kDefaultMode);
  }
};

}  // namespace aief

// docs/orbslam2.md's swap, compiled against the installed package: a fork's forward declaration,
// the replacement include/ORBextractor.h, and Tracking.cc's and Frame.cc's uses of it.
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>

namespace ORB_SLAM2 {
class ORBextractor;  // as some forks' Frame.h
}

// ---- include/ORBextractor.h, as docs/orbslam2.md gives it ----
#ifndef ORBEXTRACTOR_H
#define ORBEXTRACTOR_H
#include <aief/orbslam2_extractor.hpp>
namespace ORB_SLAM2 {
// A class, not a using-alias, so forks that forward-declare `class ORBextractor;` still compile.
class ORBextractor : public aief::ORBextractor {
 public:
  using aief::ORBextractor::ORBextractor;
  explicit ORBextractor(aief::ORBextractor&& base) : aief::ORBextractor(std::move(base)) {}
};
}  // namespace ORB_SLAM2
#endif
// ---- end of the header ----

namespace ORB_SLAM2 {

int run() {
  cv::FileStorage fSettings(
      "%YAML:1.0\nORBextractor.nFeatures: 500\nORBextractor.scaleFactor: "
      "1.2\nORBextractor.nLevels: 8\n"
      "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\nORBextractor.threads: 1\n",
      cv::FileStorage::READ | cv::FileStorage::MEMORY);
  // Tracking.cc, unchanged:
  int nFeatures = fSettings["ORBextractor.nFeatures"];
  float fScaleFactor = fSettings["ORBextractor.scaleFactor"];
  int nLevels = fSettings["ORBextractor.nLevels"];
  int fIniThFAST = fSettings["ORBextractor.iniThFAST"];
  int fMinThFAST = fSettings["ORBextractor.minThFAST"];
  ORBextractor* mpORBextractorLeft =
      new ORBextractor(nFeatures, fScaleFactor, nLevels, fIniThFAST, fMinThFAST);
  // Tracking.cc, reading our keys too:
  const aief::ExtractorOptions orbOptions = aief::ORBextractor::options_from_settings(fSettings);
  aief::ExtractorOptions iniOptions = orbOptions;
  iniOptions.n_features = 2 * orbOptions.n_features;
  ORBextractor* mpIniORBextractor = new ORBextractor(iniOptions);
  ORBextractor* fromSettings = new ORBextractor(aief::ORBextractor::from_settings(fSettings));

  // Frame.cc: ExtractORB and the accessors.
  cv::Mat im(240, 320, CV_8UC1);
  cv::theRNG().state = 3;
  cv::randu(im, cv::Scalar(0), cv::Scalar(255));
  std::vector<cv::KeyPoint> mvKeys, mvIniKeys, mvSettingsKeys;
  cv::Mat mDescriptors, mIniDescriptors, mSettingsDescriptors;
  (*mpORBextractorLeft)(im, cv::Mat(), mvKeys, mDescriptors);
  (*mpIniORBextractor)(im, cv::Mat(), mvIniKeys, mIniDescriptors);
  (*fromSettings)(im, cv::Mat(), mvSettingsKeys, mSettingsDescriptors);
  const int mnScaleLevels = mpORBextractorLeft->GetLevels();
  const float mfScaleFactor = mpORBextractorLeft->GetScaleFactor();
  const std::vector<float> mvScaleFactors = mpORBextractorLeft->GetScaleFactors();
  const std::vector<float> mvInvLevelSigma2 = mpORBextractorLeft->GetInverseScaleSigmaSquares();
  const cv::Mat& level1 = mpORBextractorLeft->mvImagePyramid[1];
  std::printf(
      "ORB-SLAM2 swap: %zu keypoints (%zu for the initialiser), %d levels, scale %.2f, level 1 "
      "%dx%d\n",
      mvKeys.size(), mvIniKeys.size(), mnScaleLevels, static_cast<double>(mfScaleFactor),
      level1.cols, level1.rows);
  const bool ok = !mvKeys.empty() && mvIniKeys.size() > mvKeys.size() &&
                  mvSettingsKeys.size() == mvKeys.size() &&
                  mDescriptors.rows == static_cast<int>(mvKeys.size()) && mnScaleLevels == 8 &&
                  mvScaleFactors.size() == 8u && mvInvLevelSigma2.size() == 8u &&
                  level1.cols == 267;
  delete mpORBextractorLeft;
  delete mpIniORBextractor;
  delete fromSettings;
  return ok ? 0 : 1;
}

}  // namespace ORB_SLAM2

int main() { return ORB_SLAM2::run(); }

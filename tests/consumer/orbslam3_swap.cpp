// docs/orbslam3.md's swap, compiled against the installed package: a fork's forward declaration,
// the replacement include/ORBextractor.h, and Tracking.cc's and Frame.cc's uses of it.
#include <cstdio>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

namespace ORB_SLAM3 {
class ORBextractor;  // as Frame.h and KeyFrame.h
}

// ---- include/ORBextractor.h, as docs/orbslam3.md gives it ----
#ifndef ORBEXTRACTOR_H
#define ORBEXTRACTOR_H
#include <aief/orbslam3_extractor.hpp>
namespace ORB_SLAM3 {
// A class, not a using-alias, so the forward declarations `class ORBextractor;` still compile.
class ORBextractor : public aief::orbslam3::ORBextractor {
 public:
  using aief::orbslam3::ORBextractor::ORBextractor;
  explicit ORBextractor(aief::orbslam3::ORBextractor&& base)
      : aief::orbslam3::ORBextractor(std::move(base)) {}
};
}  // namespace ORB_SLAM3
#endif
// ---- end of the header ----

namespace ORB_SLAM3 {

// Frame.cc's ExtractORB, unchanged.
struct Frame {
  Frame(ORBextractor* left, ORBextractor* right)
      : mpORBextractorLeft(left), mpORBextractorRight(right) {}
  ORBextractor* mpORBextractorLeft;
  ORBextractor* mpORBextractorRight;
  std::vector<cv::KeyPoint> mvKeys, mvKeysRight;
  cv::Mat mDescriptors, mDescriptorsRight;
  int monoLeft = 0, monoRight = 0;
  void ExtractORB(int flag, const cv::Mat& im, const int x0, const int x1) {
    std::vector<int> vLapping = {x0, x1};
    if (flag == 0)
      monoLeft = (*mpORBextractorLeft)(im, cv::Mat(), mvKeys, mDescriptors, vLapping);
    else
      monoRight = (*mpORBextractorRight)(im, cv::Mat(), mvKeysRight, mDescriptorsRight, vLapping);
  }
};

int run() {
  cv::FileStorage fSettings(
      "%YAML:1.0\nORBextractor.nFeatures: 500\nORBextractor.scaleFactor: "
      "1.2\nORBextractor.nLevels: 8\n"
      "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\nORBextractor.threads: 1\n",
      cv::FileStorage::READ | cv::FileStorage::MEMORY);
  // Tracking.cc (ParseORBParamFile), unchanged:
  int nFeatures = fSettings["ORBextractor.nFeatures"];
  float fScaleFactor = fSettings["ORBextractor.scaleFactor"];
  int nLevels = fSettings["ORBextractor.nLevels"];
  int fIniThFAST = fSettings["ORBextractor.iniThFAST"];
  int fMinThFAST = fSettings["ORBextractor.minThFAST"];
  ORBextractor* mpORBextractorLeft =
      new ORBextractor(nFeatures, fScaleFactor, nLevels, fIniThFAST, fMinThFAST);
  ORBextractor* mpORBextractorRight =
      new ORBextractor(nFeatures, fScaleFactor, nLevels, fIniThFAST, fMinThFAST);
  // Tracking.cc, reading our keys too:
  const aief::ExtractorOptions orbOptions =
      aief::orbslam3::ORBextractor::options_from_settings(fSettings);
  aief::ExtractorOptions iniOptions = orbOptions;
  iniOptions.n_features = 5 * orbOptions.n_features;
  ORBextractor* mpIniORBextractor = new ORBextractor(iniOptions);
  ORBextractor* fromSettings =
      new ORBextractor(aief::orbslam3::ORBextractor::from_settings(fSettings));

  cv::Mat imLeft(240, 320, CV_8UC1), imRight;
  cv::theRNG().state = 3;
  cv::randu(imLeft, cv::Scalar(0), cv::Scalar(255));
  imRight = imLeft.clone();
  // Frame.cc, stereo: both extractors in their own threads, lapping area {0, 0}.
  Frame stereo(mpORBextractorLeft, mpORBextractorRight);
  std::thread threadLeft(&Frame::ExtractORB, &stereo, 0, imLeft, 0, 0);
  std::thread threadRight(&Frame::ExtractORB, &stereo, 1, imRight, 0, 0);
  threadLeft.join();
  threadRight.join();
  // Frame.cc, monocular: {0, 1000}, the initialiser's extractor.
  Frame mono(mpIniORBextractor, nullptr);
  mono.ExtractORB(0, imLeft, 0, 1000);
  Frame settingsFrame(fromSettings, nullptr);
  settingsFrame.ExtractORB(0, imLeft, 0, 0);

  const int mnScaleLevels = mpORBextractorLeft->GetLevels();
  const float mfScaleFactor = mpORBextractorLeft->GetScaleFactor();
  const std::vector<float> mvScaleFactors = mpORBextractorLeft->GetScaleFactors();
  const std::vector<float> mvInvLevelSigma2 = mpORBextractorLeft->GetInverseScaleSigmaSquares();
  const cv::Mat& level1 = mpORBextractorRight->mvImagePyramid[1];
  std::printf(
      "ORB-SLAM3 swap: %zu + %zu stereo keypoints (%d, %d left of the lapping area), %zu for the "
      "initialiser, "
      "%d levels, scale %.2f, level 1 %dx%d\n",
      stereo.mvKeys.size(), stereo.mvKeysRight.size(), stereo.monoLeft, stereo.monoRight,
      mono.mvKeys.size(), mnScaleLevels, static_cast<double>(mfScaleFactor), level1.cols,
      level1.rows);
  const bool ok =
      !stereo.mvKeys.empty() && stereo.monoLeft == static_cast<int>(stereo.mvKeys.size()) &&
      stereo.mvKeysRight.size() == stereo.mvKeys.size() && stereo.monoRight == stereo.monoLeft &&
      mono.mvKeys.size() > stereo.mvKeys.size() && mono.monoLeft == 0 &&
      settingsFrame.mvKeys.size() == stereo.mvKeys.size() &&
      stereo.mDescriptors.rows == static_cast<int>(stereo.mvKeys.size()) && mnScaleLevels == 8 &&
      mvScaleFactors.size() == 8u && mvInvLevelSigma2.size() == 8u && level1.cols == 267;
  delete mpORBextractorLeft;
  delete mpORBextractorRight;
  delete mpIniORBextractor;
  delete fromSettings;
  return ok ? 0 : 1;
}

}  // namespace ORB_SLAM3

int main() { return ORB_SLAM3::run(); }

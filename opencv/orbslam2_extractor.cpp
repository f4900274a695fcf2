#include "aief/orbslam2_extractor.hpp"

#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/opencv.hpp"

namespace aief {

namespace {

ExtractorOptions orbslam2_options(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST) {
  ExtractorOptions options;
  options.n_features = nfeatures;
  options.scale_factor = scaleFactor;
  options.n_levels = nlevels;
  options.fast_threshold = iniThFAST;
  options.fast_min_threshold = minThFAST;
  return options;
}

}  // namespace

ORBextractor::ORBextractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST)
    : ORBextractor(orbslam2_options(nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST)) {}

ORBextractor::ORBextractor(const ExtractorOptions& options)
    : extractor_(options), nlevels(options.n_levels), scaleFactor(static_cast<float>(options.scale_factor)) {
  compute_scales();
}

void ORBextractor::compute_scales() {
  // As ORB-SLAM2's constructor: float products, sigma^2 = scale^2.
  mvScaleFactor.assign(static_cast<std::size_t>(nlevels), 1.0f);
  mvLevelSigma2.assign(static_cast<std::size_t>(nlevels), 1.0f);
  for (int i = 1; i < nlevels; ++i) {
    mvScaleFactor[static_cast<std::size_t>(i)] = mvScaleFactor[static_cast<std::size_t>(i) - 1] * scaleFactor;
    mvLevelSigma2[static_cast<std::size_t>(i)] = mvScaleFactor[static_cast<std::size_t>(i)] * mvScaleFactor[static_cast<std::size_t>(i)];
  }
  mvInvScaleFactor.resize(static_cast<std::size_t>(nlevels));
  mvInvLevelSigma2.resize(static_cast<std::size_t>(nlevels));
  for (int i = 0; i < nlevels; ++i) {
    mvInvScaleFactor[static_cast<std::size_t>(i)] = 1.0f / mvScaleFactor[static_cast<std::size_t>(i)];
    mvInvLevelSigma2[static_cast<std::size_t>(i)] = 1.0f / mvLevelSigma2[static_cast<std::size_t>(i)];
  }
}

ORBextractor ORBextractor::from_settings(const cv::FileStorage& settings) {
  ExtractorOptions options;
  const auto read_int = [&](const char* key, int& value) {
    const cv::FileNode node = settings[key];
    if (!node.empty()) {
      if (!node.isInt() && !node.isReal()) throw Error(std::string(key) + " must be a number");
      value = static_cast<int>(node.real());
    }
  };
  read_int("ORBextractor.nFeatures", options.n_features);
  read_int("ORBextractor.nLevels", options.n_levels);
  read_int("ORBextractor.iniThFAST", options.fast_threshold);
  read_int("ORBextractor.minThFAST", options.fast_min_threshold);
  read_int("ORBextractor.blockSize", options.block_size);
  if (const cv::FileNode node = settings["ORBextractor.scaleFactor"]; !node.empty()) {
    if (!node.isInt() && !node.isReal()) throw Error("ORBextractor.scaleFactor must be a number");
    options.scale_factor = node.real();
  }
  if (const cv::FileNode node = settings["ORBextractor.mode"]; !node.empty()) options = options_for_mode(parse_mode(static_cast<std::string>(node)), options);
  if (const cv::FileNode node = settings["ORBextractor.entropyThreshold"]; !node.empty()) {
    if (node.isString() && static_cast<std::string>(node) == "auto") options.auto_threshold = true;
    else if (node.isInt() || node.isReal()) options.entropy_threshold = node.real();
    else throw Error("ORBextractor.entropyThreshold must be a number or \"auto\"");
  }
  return ORBextractor(options);
}

void ORBextractor::operator()(cv::InputArray image, cv::InputArray /*mask: ignored, as ORB-SLAM2*/, std::vector<cv::KeyPoint>& keypoints,
                              cv::OutputArray descriptors) {
  const cv::Mat input = image.getMat();
  if (input.empty()) throw Error("image is empty");
  const cv::Mat* gray = &input;
  if (input.type() == CV_8UC3) {
    cv::cvtColor(input, gray_, cv::COLOR_BGR2GRAY);
    gray = &gray_;
  } else if (input.type() == CV_8UC4) {
    cv::cvtColor(input, gray_, cv::COLOR_BGRA2GRAY);
    gray = &gray_;
  } else if (input.type() != CV_8UC1) {
    throw Error("image type " + std::to_string(input.type()) + " is not CV_8UC1, CV_8UC3 or CV_8UC4");
  }
  extractor_.extract({gray->data, gray->cols, gray->rows, static_cast<std::ptrdiff_t>(gray->step)}, features_);
  keypoints = to_cv_keypoints(features_);
  to_cv_descriptors(features_).copyTo(descriptors);
  mvImagePyramid.resize(static_cast<std::size_t>(nlevels));
  for (int n = 0; n < nlevels; ++n) {
    const ImageView level = extractor_.pyramid_level(n);
    mvImagePyramid[static_cast<std::size_t>(n)] =
        level.empty() ? cv::Mat() : cv::Mat(level.height, level.width, CV_8UC1, const_cast<std::uint8_t*>(level.data), static_cast<std::size_t>(level.stride));
  }
}

}  // namespace aief

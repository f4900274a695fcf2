#include "aief/orbslam_extractor_base.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "aief/error.hpp"
#include "opencv/cv_conversions.hpp"

namespace aief {

namespace {

// Where the drop-ins put a keypoint: ORB-SLAM's convention, level pixel x (an integer) at
// x * scale_n in level 0. Frame::ComputeStereoMatches (ORB-SLAM2 and ORB-SLAM3) centres its SAD
// window at round(x / scale_n) in mvImagePyramid and takes the disparity from x itself, so a
// sub-pixel or pixel-centre x shifts that keypoint's disparity by x - scale_n * round(x / scale_n):
// up to half a level pixel, times scale_n (docs/slam.md, "Stereo"). The engine's own defaults
// (pixel-centre, sub-pixel) stay for everything else.
ExtractorOptions with_orbslam_keypoint_convention(ExtractorOptions options) {
  options.coordinates = CoordinateMap::scaled;
  options.subpixel = false;
  return options;
}

ExtractorOptions orbslam_options(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST) {
  ExtractorOptions options = with_orbslam_keypoint_convention({});
  options.n_features = nfeatures;
  options.scale_factor = scaleFactor;
  options.n_levels = nlevels;
  options.fast_threshold = iniThFAST;
  options.fast_min_threshold = minThFAST;
  return options;
}

double read_number(const cv::FileNode& node, const char* key) {
  if (!node.isInt() && !node.isReal()) throw Error(std::string(key) + " must be a number");
  return node.real();
}

// ORB-SLAM reads these with an int conversion that truncates; a fractional or huge value is a
// typo we would rather name than silently change.
void read_int(const cv::FileStorage& settings, const char* key, int& value) {
  const cv::FileNode node = settings[key];
  if (node.empty()) return;
  const double number = read_number(node, key);
  if (number != std::floor(number) || number < std::numeric_limits<int>::min() || number > std::numeric_limits<int>::max())
    throw Error(std::string(key) + " must be an integer, got " + std::to_string(number));
  value = static_cast<int>(number);
}

}  // namespace

OrbSlamExtractorBase::OrbSlamExtractorBase(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST)
    : OrbSlamExtractorBase(orbslam_options(nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST)) {}

OrbSlamExtractorBase::OrbSlamExtractorBase(const ExtractorOptions& options)
    : extractor_(options), nlevels(options.n_levels), scaleFactor(static_cast<float>(options.scale_factor)) {
  compute_scales();
}

void OrbSlamExtractorBase::compute_scales() {
  // As ORB-SLAM's constructor: float products, sigma^2 = scale^2. (ORB-SLAM3 keeps scaleFactor
  // as a double, but the product of two floats is exact in double, so rounding it to float
  // gives the float product: the same tables.)
  const auto levels = static_cast<std::size_t>(nlevels);
  mvScaleFactor.assign(levels, 1.0f);
  mvLevelSigma2.assign(levels, 1.0f);
  for (std::size_t i = 1; i < levels; ++i) {
    mvScaleFactor[i] = mvScaleFactor[i - 1] * scaleFactor;
    mvLevelSigma2[i] = mvScaleFactor[i] * mvScaleFactor[i];
  }
  mvInvScaleFactor.resize(levels);
  mvInvLevelSigma2.resize(levels);
  for (std::size_t i = 0; i < levels; ++i) {
    mvInvScaleFactor[i] = 1.0f / mvScaleFactor[i];
    mvInvLevelSigma2[i] = 1.0f / mvLevelSigma2[i];
  }
}

ExtractorOptions OrbSlamExtractorBase::options_from_settings(const cv::FileStorage& settings) {
  if (!settings.isOpened()) throw Error("settings file is not open");
  ExtractorOptions options = with_orbslam_keypoint_convention({});
  read_int(settings, "ORBextractor.nFeatures", options.n_features);
  read_int(settings, "ORBextractor.nLevels", options.n_levels);
  read_int(settings, "ORBextractor.iniThFAST", options.fast_threshold);
  read_int(settings, "ORBextractor.minThFAST", options.fast_min_threshold);
  read_int(settings, "ORBextractor.blockSize", options.block_size);
  read_int(settings, "ORBextractor.threads", options.threads);
  if (const cv::FileNode node = settings["ORBextractor.scaleFactor"]; !node.empty())
    options.scale_factor = static_cast<float>(read_number(node, "ORBextractor.scaleFactor"));  // float, as Tracking.cc
  if (const cv::FileNode node = settings["ORBextractor.mode"]; !node.empty()) {
    if (!node.isString()) throw Error("ORBextractor.mode must be aief, orbslam2 or quadtree-entropy");
    options = with_orbslam_keypoint_convention(options_for_mode(parse_mode(static_cast<std::string>(node)), options));
  }
  if (const cv::FileNode node = settings["ORBextractor.coordinates"]; !node.empty()) {
    if (!node.isString()) throw Error("ORBextractor.coordinates must be scaled or pixel-centre");
    options.coordinates = parse_coordinate_map(static_cast<std::string>(node));
  }
  if (const cv::FileNode node = settings["ORBextractor.subpixel"]; !node.empty()) {
    int subpixel = 0;
    read_int(settings, "ORBextractor.subpixel", subpixel);
    if (subpixel != 0 && subpixel != 1) throw Error("ORBextractor.subpixel must be 0 or 1, got " + std::to_string(subpixel));
    options.subpixel = subpixel == 1;
  }
  if (const cv::FileNode node = settings["ORBextractor.candidatePool"]; !node.empty()) {
    if (node.isString()) options.candidate_pool = parse_candidate_pool(static_cast<std::string>(node));
    else options.candidate_pool = read_number(node, "ORBextractor.candidatePool");
  }
  if (const cv::FileNode node = settings["ORBextractor.entropyThreshold"]; !node.empty()) {
    if (node.isString() && static_cast<std::string>(node) == "auto") options.auto_threshold = true;
    else if (node.isInt() || node.isReal()) options.entropy_threshold = node.real();
    else throw Error("ORBextractor.entropyThreshold must be a number or \"auto\"");
  }
  return options;
}

const Features& OrbSlamExtractorBase::extract_frame(cv::InputArray image) {
  const cv::Mat input = image.getMat();  // named: gray_of may return a reference to it
  const cv::Mat& gray = detail::gray_of(input, gray_);
  extractor_.extract({gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)}, features_);
  mvImagePyramid.resize(static_cast<std::size_t>(nlevels));
  // Level 0 is the gray input itself (sharing its reference count, so it outlives the caller's
  // Mat); the others are headers over the extractor's buffers, valid until the next call.
  mvImagePyramid[0] = gray;
  for (int n = 1; n < nlevels; ++n) {
    const ImageView level = extractor_.pyramid_level(n);
    mvImagePyramid[static_cast<std::size_t>(n)] =
        level.empty() ? cv::Mat() : cv::Mat(level.height, level.width, CV_8UC1, const_cast<std::uint8_t*>(level.data), static_cast<std::size_t>(level.stride));
  }
  return features_;
}

}  // namespace aief

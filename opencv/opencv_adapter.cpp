#include "aief/opencv.hpp"

#include <string>

#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "opencv/gray_image.hpp"

namespace aief {

namespace detail {

const cv::Mat& gray_of(const cv::Mat& image, cv::Mat& buffer) {
  if (image.empty()) throw Error("image is empty");
  if (image.depth() != CV_8U) throw Error("image depth " + std::to_string(image.depth()) + " is not 8-bit unsigned (CV_8U)");
  switch (image.channels()) {
    case 1: return image;
    case 3: cv::cvtColor(image, buffer, cv::COLOR_BGR2GRAY); return buffer;
    case 4: cv::cvtColor(image, buffer, cv::COLOR_BGRA2GRAY); return buffer;
    default: throw Error("image has " + std::to_string(image.channels()) + " channels (expected 1, 3 or 4)");
  }
}

}  // namespace detail

std::vector<cv::KeyPoint> to_cv_keypoints(const Features& features) {
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(features.keypoints.size());
  for (const Keypoint& kp : features.keypoints)
    keypoints.emplace_back(cv::Point2f(kp.x, kp.y), kp.size, kp.angle_deg, kp.response, kp.octave, -1);
  return keypoints;
}

cv::Mat to_cv_descriptors(const Features& features) {
  cv::Mat descriptors(static_cast<int>(features.descriptors.size()), kDescriptorBytes, CV_8U);
  for (int r = 0; r < descriptors.rows; ++r)
    std::copy(features.descriptors[static_cast<std::size_t>(r)].begin(), features.descriptors[static_cast<std::size_t>(r)].end(),
              descriptors.ptr<std::uint8_t>(r));
  return descriptors;
}

CvExtractor::CvExtractor(ExtractorOptions options) : extractor_(options) {}

void CvExtractor::detect_and_compute(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) {
  const cv::Mat& gray = detail::gray_of(image, gray_);
  extractor_.extract({gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)}, features_);
  keypoints = to_cv_keypoints(features_);
  descriptors = to_cv_descriptors(features_);
}

void cv_extract(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors, const ExtractorOptions& options) {
  CvExtractor(options).detect_and_compute(image, keypoints, descriptors);
}

}  // namespace aief

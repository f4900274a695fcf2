#include "aief/opencv.hpp"

#include <algorithm>
#include <string>

#include <opencv2/core/check.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "opencv/cv_conversions.hpp"

namespace aief {

namespace detail {

const cv::Mat& gray_of(const cv::Mat& image, cv::Mat& buffer) {
  if (image.empty()) throw Error("image is empty");
  if (image.depth() != CV_8U)
    throw Error("image of type " + cv::typeToString(image.type()) + " (depth " +
                cv::depthToString(image.depth()) +
                ") is not 8-bit unsigned (CV_8U): convert it first (convertTo)");
  switch (image.channels()) {
    case 1: return image;
    case 3: cv::cvtColor(image, buffer, cv::COLOR_BGR2GRAY); return buffer;
    case 4: cv::cvtColor(image, buffer, cv::COLOR_BGRA2GRAY); return buffer;
    default:
      throw Error("image has " + std::to_string(image.channels()) +
                  " channels (expected 1, 3 or 4)");
  }
}

void fill_cv_keypoints(const Features& features, std::vector<cv::KeyPoint>& keypoints) {
  keypoints.clear();
  keypoints.reserve(features.keypoints.size());
  for (const Keypoint& kp : features.keypoints) keypoints.push_back(to_cv_keypoint(kp));
}

void fill_cv_descriptors(const Features& features, cv::OutputArray descriptors,
                         bool release_when_empty) {
  if (features.descriptors.empty() && release_when_empty) {
    descriptors.release();
    return;
  }
  descriptors.create(static_cast<int>(features.descriptors.size()), kDescriptorBytes, CV_8U);
  cv::Mat out = descriptors.getMat();
  for (int r = 0; r < out.rows; ++r) {
    const Descriptor& d = features.descriptors[static_cast<std::size_t>(r)];
    std::copy(d.begin(), d.end(), out.ptr<std::uint8_t>(r));
  }
}

}  // namespace detail

std::vector<cv::KeyPoint> to_cv_keypoints(const Features& features) {
  std::vector<cv::KeyPoint> keypoints;
  detail::fill_cv_keypoints(features, keypoints);
  return keypoints;
}

cv::Mat to_cv_descriptors(const Features& features) {
  cv::Mat descriptors;
  detail::fill_cv_descriptors(features, descriptors, false);
  return descriptors;
}

CvExtractor::CvExtractor(ExtractorOptions options) : extractor_(options) {}

void CvExtractor::detect_and_compute(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints,
                                     cv::Mat& descriptors) {
  const cv::Mat& gray = detail::gray_of(image, gray_);
  extractor_.extract(view_of(gray), features_);
  detail::fill_cv_keypoints(features_, keypoints);
  detail::fill_cv_descriptors(features_, descriptors, false);
}

void cv_extract(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
                const ExtractorOptions& options) {
  CvExtractor(options).detect_and_compute(image, keypoints, descriptors);
}

}  // namespace aief

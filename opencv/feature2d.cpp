#include "aief/feature2d.hpp"

#include <string>

#include "aief/error.hpp"
#include "opencv/cv_conversions.hpp"

namespace aief::opencv {

namespace {

// The mask rule of cv::Feature2D: CV_8UC1 of the image's size (the engine checks the size).
ImageView mask_view(cv::InputArray mask) {
  if (mask.empty()) return {};
  const cv::Mat m = mask.getMat();
  if (m.type() != CV_8UC1) throw Error("mask must be CV_8UC1, got " + cv::typeToString(m.type()));
  return view_of(m);
}

Keypoint from_cv_keypoint(const cv::KeyPoint& kp) {
  Keypoint out;
  out.x = kp.pt.x;
  out.y = kp.pt.y;
  out.size = kp.size;
  out.angle_deg = kp.angle;
  out.response = kp.response;
  out.octave = kp.octave;
  return out;
}

}  // namespace

cv::Ptr<Feature2D> Feature2D::create(const ExtractorOptions& options, GivenAngles given_angles) {
  return cv::makePtr<Feature2D>(options, given_angles);
}

Feature2D::Feature2D(const ExtractorOptions& options, GivenAngles given_angles)
    : extractor_(options), given_angles_(given_angles) {}

void Feature2D::detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                                 cv::OutputArray descriptors, bool useProvidedKeypoints) {
  const cv::Mat input = image.getMat();
  const cv::Mat& gray = detail::gray_of(input, gray_);
  if (useProvidedKeypoints) {
    given_.clear();
    given_.reserve(keypoints.size());
    for (const cv::KeyPoint& kp : keypoints) given_.push_back(from_cv_keypoint(kp));
    extractor_.describe(view_of(gray), given_, features_, &kept_, given_angles_);
    // The kept keypoints as given (class_id and all), with the recomputed angle.
    for (std::size_t k = 0; k < kept_.size(); ++k) {
      keypoints[k] = keypoints[static_cast<std::size_t>(kept_[k])];
      keypoints[k].angle = features_.keypoints[k].angle_deg;
    }
    keypoints.resize(kept_.size());
  } else {
    extractor_.extract(view_of(gray), mask_view(mask), features_);
    detail::fill_cv_keypoints(features_, keypoints);
  }
  if (descriptors.needed()) detail::fill_cv_descriptors(features_, descriptors, true);
}

void Feature2D::write(cv::FileStorage& storage) const {
  (void)storage;  // filled from the option table (core/option_table.hpp) once it lands
}

void Feature2D::read(const cv::FileNode& node) {
  (void)node;
}

}  // namespace aief::opencv

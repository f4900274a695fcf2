#include "aief/orbslam2_extractor.hpp"

#include "opencv/cv_conversions.hpp"

namespace aief {

ORBextractor ORBextractor::from_settings(const cv::FileStorage& settings) {
  return ORBextractor(options_from_settings(settings));
}

void ORBextractor::operator()(cv::InputArray image, cv::InputArray /*mask: ignored, as ORB-SLAM2*/,
                              std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors) {
  const Features& features = extract_frame(image);
  detail::fill_cv_keypoints(features, keypoints);
  detail::fill_cv_descriptors(features, descriptors, true);  // released when empty, as ORB-SLAM2
}

}  // namespace aief

#include "aief/orbslam3_extractor.hpp"

#include <algorithm>
#include <string>

#include "aief/error.hpp"
#include "opencv/cv_conversions.hpp"

namespace aief::orbslam3 {

ORBextractor ORBextractor::from_settings(const cv::FileStorage& settings) {
  return ORBextractor(options_from_settings(settings));
}

int ORBextractor::operator()(cv::InputArray image, cv::InputArray /*mask: ignored, as ORB-SLAM3*/,
                             std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                             std::vector<int>& vLappingArea) {
  if (image.empty()) return -1;  // ORB-SLAM3's answer, outputs untouched
  if (vLappingArea.size() < 2)
    throw Error("vLappingArea must hold two bounds (x0, x1), got " +
                std::to_string(vLappingArea.size()) + " values");
  const Features& features = extract_frame(image);
  const std::size_t count = features.keypoints.size();
  keypoints.resize(count);
  if (count == 0) {
    descriptors.release();  // as ORB-SLAM3
    return 0;
  }
  descriptors.create(static_cast<int>(count), kDescriptorBytes, CV_8U);
  cv::Mat rows = descriptors.getMat();
  // ORB-SLAM3 compares the float x with the int bounds, which converts the bounds to float.
  const auto lapping_first = static_cast<float>(vLappingArea[0]);
  const auto lapping_last = static_cast<float>(vLappingArea[1]);
  std::size_t mono_index = 0;        // ORB-SLAM3's monoIndex: the next slot from the front
  std::size_t stereo_index = count;  // one past ORB-SLAM3's stereoIndex: slots from the back
  for (std::size_t i = 0; i < count; ++i) {
    const Keypoint& kp = features.keypoints[i];
    const bool in_lapping_area = kp.x >= lapping_first && kp.x <= lapping_last;
    const std::size_t slot = in_lapping_area ? --stereo_index : mono_index++;
    keypoints[slot] = detail::to_cv_keypoint(kp);
    std::copy(features.descriptors[i].begin(), features.descriptors[i].end(),
              rows.ptr<std::uint8_t>(static_cast<int>(slot)));
  }
  return static_cast<int>(mono_index);
}

}  // namespace aief::orbslam3

#pragma once
// Conversions shared by CvExtractor and ORBextractor (not installed). They write into the
// caller's containers so that a steady stream of frames reuses their storage.
#include <vector>

#include <opencv2/core.hpp>

#include "aief/cv_image_view.hpp"
#include "aief/features.hpp"

namespace aief::detail {

// The adapter's input rule: 8-bit images with 1, 3 (BGR) or 4 (BGRA) channels; colour is
// converted as cv::cvtColor does, gray is used in place. Returns `image` itself when it is gray,
// else its conversion written into `buffer`. Throws aief::Error naming the depth or channel
// count of anything else, or an empty image.
const cv::Mat& gray_of(const cv::Mat& image, cv::Mat& buffer);

// One keypoint as cv::KeyPoint: pt in level-0 pixels, size, angle (degrees), response (FAST
// score), octave, class_id -1.
inline cv::KeyPoint to_cv_keypoint(const Keypoint& kp) {
  return {cv::Point2f(kp.x, kp.y), kp.size, kp.angle_deg, kp.response, kp.octave, -1};
}

// keypoints := the features' keypoints as cv::KeyPoint (to_cv_keypoint), keeping its capacity.
void fill_cv_keypoints(const Features& features, std::vector<cv::KeyPoint>& keypoints);

// descriptors := N x 32 CV_8U rows; Mat::create reuses the storage when N is unchanged.
// With release_when_empty, no keypoint releases the matrix (ORB-SLAM2's behaviour), otherwise
// it becomes 0 x 32.
void fill_cv_descriptors(const Features& features, cv::OutputArray descriptors,
                         bool release_when_empty);

}  // namespace aief::detail

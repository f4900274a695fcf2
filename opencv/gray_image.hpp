#pragma once
// The adapter's input rule, shared by CvExtractor and ORBextractor: 8-bit images with 1, 3 (BGR)
// or 4 (BGRA) channels; colour is converted as cv::cvtColor does, gray is used in place.
#include <opencv2/core.hpp>

namespace aief::detail {

// Returns `image` itself when it is 8-bit gray, else its gray conversion written into `buffer`.
// Throws aief::Error naming the depth or channel count of anything else, or an empty image.
const cv::Mat& gray_of(const cv::Mat& image, cv::Mat& buffer);

}  // namespace aief::detail

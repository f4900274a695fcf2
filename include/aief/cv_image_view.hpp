#pragma once
// A gray cv::Mat seen as the engine's image view, without a copy: the one conversion every
// OpenCV-facing part of the project uses (header-only; needs OpenCV's core headers).
#include <string>

#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "aief/image.hpp"

namespace aief {

namespace detail {
inline void check_gray_mat(const cv::Mat& gray) {
  if (!gray.empty() && (gray.type() != CV_8UC1 || gray.dims != 2))
    throw Error("expected a 2-D 8-bit one-channel image (CV_8UC1), got type " +
                cv::typeToString(gray.type()) + " with " + std::to_string(gray.dims) +
                " dimensions");
}
}  // namespace detail

// The pixels of a CV_8UC1 matrix, row stride included (a ROI is viewed in place). An empty
// matrix gives an empty view (which the extractor refuses, naming it). Throws aief::Error for
// any other type.
inline ImageView view_of(const cv::Mat& gray) {
  detail::check_gray_mat(gray);
  if (gray.empty()) return {};
  return {gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)};
}

// The same, writable.
inline MutableImageView mutable_view_of(cv::Mat& gray) {
  detail::check_gray_mat(gray);
  if (gray.empty()) return {};
  return {gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)};
}

}  // namespace aief

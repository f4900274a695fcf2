#pragma once
// OpenCV adapter (target aief::opencv): cv::Mat in, cv::KeyPoint and an N x 32 CV_8U descriptor
// matrix out, so a program using cv::ORB switches in a few lines (docs/opencv.md).
#include <vector>

#include <opencv2/core.hpp>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/extractor.hpp"

namespace aief {

// Reusable: keeps one Extractor (buffers, kernel table) across frames.
class CvExtractor {
 public:
  explicit CvExtractor(ExtractorOptions options = {});

  // image: CV_8UC1, or CV_8UC3 / CV_8UC4 (converted to gray as OpenCV's cvtColor). Keypoints
  // carry pt (level-0 pixels), size, angle (degrees), response (FAST score), octave, class_id -1.
  // Throws aief::Error for an empty or unsupported image.
  void detect_and_compute(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints,
                          cv::Mat& descriptors);

  const Extractor& extractor() const { return extractor_; }

 private:
  Extractor extractor_;
  Features features_;
  cv::Mat gray_;
};

// One-shot form of CvExtractor::detect_and_compute.
void cv_extract(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
                const ExtractorOptions& options = {});

// Conversions used by the adapter, public for callers that hold aief::Features already.
std::vector<cv::KeyPoint> to_cv_keypoints(const Features& features);
cv::Mat to_cv_descriptors(const Features& features);

}  // namespace aief

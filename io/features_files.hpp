#pragma once
// Result files: features as JSON or as OpenCV FileStorage YAML (read back by cv::FileStorage and
// Python's cv2.FileStorage: "keypoints" as cv::KeyPoint list, "descriptors" an N x 32 CV_8U
// matrix). Both written atomically (temporary file, then rename).
#include <string>

#include "aief/features.hpp"
#include "aief/options.hpp"

namespace aief::io {

// JSON: {"image", "width", "height", "options": {...}, "info": {...},
//        "keypoints": [{"x", "y", "size", "angle", "response", "octave"}],
//        "descriptors_hex": ["64 hex chars", ...]}
std::string features_json(const std::string& image_path, const Features& features, const ExtractorOptions& options);
void write_features_json(const std::string& path, const std::string& image_path, const Features& features,
                         const ExtractorOptions& options);

void write_features_yaml(const std::string& path, const std::string& image_path, const Features& features);

// By extension: .json, .yml / .yaml, or .npz (io/npz_writer.hpp). Throws aief::Error for another extension.
void write_features(const std::string& path, const std::string& image_path, const Features& features,
                    const ExtractorOptions& options);

}  // namespace aief::io

#pragma once
// Result files: features as JSON or as OpenCV FileStorage YAML (read back by cv::FileStorage and
// Python's cv2.FileStorage: "keypoints" as cv::KeyPoint list, "descriptors" an N x 32 CV_8U
// matrix). Both written atomically (temporary file, then rename). Chosen by extension through
// io/feature_formats.hpp, the table of every format.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aief/features.hpp"
#include "aief/options.hpp"
#include "io/source_record.hpp"

namespace aief::io {

// What a JSON / YAML result at `path` records: whether it is complete and of `source`, and its
// option record (io/feature_formats.hpp asks by extension).
OutputRecord json_file_record(const std::string& path, const SourceRecord& source);
OutputRecord yaml_file_record(const std::string& path, const SourceRecord& source);

// Throws aief::Error when YAML cannot hold these names and read them back: no control character
// but tab, LF and CR, at most 4094 bytes escaped (JSON and npz hold any).
void check_yaml_can_hold(const std::string& image_path, const std::string& source_name);

// JSON: {"image", "source": {"name", "bytes", "mtime_ns"} (when given), "width", "height",
// "options": {...}, "info": {...},
//        "keypoints": [{"x", "y", "size", "angle", "response", "octave"}],
//        "descriptors_hex": ["64 hex chars", ...]}
std::string features_json(const std::string& image_path, const Features& features,
                          const ExtractorOptions& options,
                          const std::optional<SourceRecord>& source = std::nullopt);
void write_features_json(const std::string& path, const std::string& image_path,
                         const Features& features, const ExtractorOptions& options,
                         const std::optional<SourceRecord>& source = std::nullopt);

// YAML: image, source_name / source_bytes / source_mtime_ns (strings: FileStorage integers are
// 32-bit), width, height, options (the option record as one JSON string, io/option_record.hpp),
// keypoints, descriptors.
void write_features_yaml(const std::string& path, const std::string& image_path,
                         const Features& features, const ExtractorOptions& options,
                         const std::optional<SourceRecord>& source = std::nullopt);

}  // namespace aief::io

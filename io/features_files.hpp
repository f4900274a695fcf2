#pragma once
// Result files: features as JSON or as OpenCV FileStorage YAML (read back by cv::FileStorage and
// Python's cv2.FileStorage: "keypoints" as cv::KeyPoint list, "descriptors" an N x 32 CV_8U
// matrix). Both written atomically (temporary file, then rename).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aief/features.hpp"
#include "aief/options.hpp"
#include "io/source_record.hpp"

namespace aief::io {

// What the result file `output_path` (.json, .yml / .yaml, .npz) records: whether it is complete
// and of `source` (false when it is missing, cut short, unreadable, or from another input), and
// its option record. One read of the file for both.
OutputRecord features_file_record(const std::string& output_path, const SourceRecord& source);
bool features_file_belongs_to(const std::string& output_path, const SourceRecord& source);

// True when write_features accepts the path's extension: the CLI asks before any work.
bool is_features_file_name(const std::string& path);

// Throws aief::Error when the format of `output_path` cannot hold these names and read them back
// (YAML: no control character but tab, LF and CR, at most 4094 bytes escaped; JSON and npz hold
// any). Commands ask before any work, so that such an image is not extracted for nothing.
void check_features_file_can_hold(const std::string& output_path, const std::string& image_path,
                                  const std::string& source_name);

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

// By extension: .json, .yml / .yaml, or .npz (io/npz_writer.hpp). Throws aief::Error for another
// extension.
void write_features(const std::string& path, const std::string& image_path,
                    const Features& features, const ExtractorOptions& options,
                    const std::optional<SourceRecord>& source = std::nullopt);

}  // namespace aief::io

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

namespace aief::io {

// The image file a result came from, recorded in the result ("source") so that a resumed batch
// can tell whether an output belongs to its input: the same name, size and modification time.
struct SourceRecord {
  std::string name;         // the input's relative name as listed (the batch key), never symlink-resolved
  std::uintmax_t bytes = 0;  // file size
  long long mtime_ns = 0;    // modification time, nanoseconds since the epoch
};

// The record of the file at `path` (symlinks followed: the size and time of what is read),
// under `name`. Throws aief::Error when the file cannot be examined.
SourceRecord source_record_of(const std::string& path, const std::string& name);

// True when `output_path` is a complete result file (.json, .yml / .yaml) whose source record
// equals `source`; false when it is missing, cut short, unreadable, or from another input.
bool features_file_belongs_to(const std::string& output_path, const SourceRecord& source);

// True when write_features accepts the path's extension: the CLI asks before any work.
bool is_features_file_name(const std::string& path);

// JSON: {"image", "source": {"name", "bytes", "mtime_ns"} (when given), "width", "height", "options": {...}, "info": {...},
//        "keypoints": [{"x", "y", "size", "angle", "response", "octave"}],
//        "descriptors_hex": ["64 hex chars", ...]}
std::string features_json(const std::string& image_path, const Features& features, const ExtractorOptions& options,
                          const std::optional<SourceRecord>& source = std::nullopt);
void write_features_json(const std::string& path, const std::string& image_path, const Features& features,
                         const ExtractorOptions& options, const std::optional<SourceRecord>& source = std::nullopt);

// YAML: image, source_name / source_bytes / source_mtime_ns (strings: FileStorage integers are
// 32-bit), width, height, keypoints, descriptors.
void write_features_yaml(const std::string& path, const std::string& image_path, const Features& features,
                         const std::optional<SourceRecord>& source = std::nullopt);

// By extension: .json, or .yml / .yaml. Throws aief::Error for another extension.
void write_features(const std::string& path, const std::string& image_path, const Features& features,
                    const ExtractorOptions& options, const std::optional<SourceRecord>& source = std::nullopt);

}  // namespace aief::io

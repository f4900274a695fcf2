#pragma once
// Features as a numpy .npz (numpy.load reads it; no numpy needed to write): an uncompressed
// zip of .npy arrays (format 1.0, little-endian):
//   keypoints N x 2 float32 (pixel centres at integers, as aief returns them), descriptors
//   N x 32 uint8, scores N float32 (FAST response), size N float32, angle N float32 (degrees),
//   octave N int32, image_size 2 int64 (width, height), options (a bytes scalar, the option
//   record as JSON text, io/option_record.hpp); with a source record (a batch) also
//   source_name (a bytes scalar, the input's name) and source_stat 2 int64 (bytes, mtime_ns).
#include <optional>
#include <string>

#include "aief/features.hpp"
#include "aief/options.hpp"
#include "io/source_record.hpp"

namespace aief::io {

std::string features_npz(const Features& features, const ExtractorOptions& options,
                         const std::optional<SourceRecord>& source = std::nullopt);
// Written atomically (temporary file, then rename). Throws aief::Error naming the file.
void write_features_npz(const std::string& path, const Features& features,
                        const ExtractorOptions& options,
                        const std::optional<SourceRecord>& source = std::nullopt);

// What an .npz written here records: complete (its zip directory ends it) and holding exactly
// `source`, and its "options" member.
OutputRecord npz_file_record(const std::string& path, const SourceRecord& source);

}  // namespace aief::io

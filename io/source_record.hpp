#pragma once
// The image file a result came from, recorded in the result ("source") so that a resumed batch
// can tell whether an output belongs to its input: the same name, size and modification time.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace aief::io {

struct SourceRecord {
  std::string name;  // the input's relative name as listed (the batch key), never symlink-resolved
  std::uintmax_t bytes = 0;  // file size
  long long mtime_ns = 0;    // modification time, nanoseconds since the epoch
  // What reading the file reported (io::read_gray_image's warnings): written into the result's
  // "info" as "decoder_warnings", not part of the identity a resume compares.
  std::vector<std::string> warnings;
};

// What an output file records of its making, as read back for a resume.
struct OutputRecord {
  bool of_source = false;  // complete, and records exactly the source asked about
  // Its option record, JSON text (io/option_record.hpp); nullopt: it has none (an older aief's)
  // or it cannot be read.
  std::optional<std::string> options;
};

// The record of the file at `path` (symlinks followed: the size and time of what is read),
// under `name`. Throws aief::Error when the file cannot be examined.
SourceRecord source_record_of(const std::string& path, const std::string& name);

}  // namespace aief::io

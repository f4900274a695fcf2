#pragma once
// A small streaming JSON writer: enough for result files, no dependency. Numbers are written
// with enough digits to read back the same float or double.
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "aief/error.hpp"

namespace aief::io {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view name);  // inside an object, before each value

  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(float number);
  JsonWriter& value(int number);
  JsonWriter& value(long long number);
  JsonWriter& value(bool flag);

  // key + value in one call.
  template <class T>
  JsonWriter& field(std::string_view name, const T& v) {
    key(name);
    return value(v);
  }

  // Line breaks after array elements at this depth or above keep big files readable.
  void set_newline_depth(int depth) { newline_depth_ = depth; }

 private:
  void before_value();
  std::ostream& out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
  int newline_depth_ = 2;
};

std::string hex_of(const std::uint8_t* bytes, std::size_t count);

// A file that could not be written. `of_the_disk`: the cause is the file system, not this one
// file (no space, quota, read-only, I/O error): a batch stops rather than fail every image.
class WriteError : public Error {
 public:
  WriteError(const std::string& message, bool of_the_disk)
      : Error(message), of_the_disk_(of_the_disk) {}
  bool of_the_disk() const { return of_the_disk_; }

 private:
  bool of_the_disk_;
};

// Whether the system error `code` (errno) is the file system's rather than one file's.
bool is_disk_failure(int code);

// Writes `content` to `path` atomically: a temporary file beside it, then rename, so an
// interrupted run never leaves a half-written result, and a failed one leaves no temporary.
// The temporary is this write's own (unique_temporary_path_of, created exclusively and locked
// while written): two processes writing the same output (a batch resubmitted while the first
// still runs) each rename a whole file of their own, and the output is whole either way.
// Throws WriteError with the system's reason.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace aief::io

#include "io/json_writer.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/temporary_files.hpp"

namespace aief::io {

void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!first_.empty()) {
    if (!first_.back()) out_ << ',';
    if (static_cast<int>(first_.size()) <= newline_depth_)
      out_ << '\n' << std::string(first_.size() * 2, ' ');
    first_.back() = false;
  }
}

JsonWriter& JsonWriter::begin_object() {
  before_value();
  out_ << '{';
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty && static_cast<int>(first_.size()) < newline_depth_)
    out_ << '\n' << std::string(first_.size() * 2, ' ');
  out_ << '}';
  if (first_.empty()) out_ << '\n';
  return *this;
}

JsonWriter& JsonWriter::begin_array() {
  before_value();
  out_ << '[';
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty && static_cast<int>(first_.size()) < newline_depth_)
    out_ << '\n' << std::string(first_.size() * 2, ' ');
  out_ << ']';
  return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
  value(name);
  out_ << ':';
  after_key_ = true;
  return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) {
  before_value();
  out_ << '"';
  for (char c : text) {
    switch (c) {
      case '"': out_ << "\\\""; break;
      case '\\': out_ << "\\\\"; break;
      case '\n': out_ << "\\n"; break;
      case '\t': out_ << "\\t"; break;
      case '\r': out_ << "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out_ << buffer;
        } else {
          out_ << c;
        }
    }
  }
  out_ << '"';
  return *this;
}

JsonWriter& JsonWriter::value(double number) {
  before_value();
  if (!std::isfinite(number)) {
    out_ << "null";  // JSON has no NaN or infinity
    return *this;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", number);
  out_ << buffer;
  return *this;
}

JsonWriter& JsonWriter::value(float number) {
  before_value();
  if (!std::isfinite(number)) {
    out_ << "null";
    return *this;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(number));
  out_ << buffer;
  return *this;
}

JsonWriter& JsonWriter::value(int number) { return value(static_cast<long long>(number)); }

JsonWriter& JsonWriter::value(long long number) {
  before_value();
  out_ << number;
  return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
  before_value();
  out_ << (flag ? "true" : "false");
  return *this;
}

std::string hex_of(const std::uint8_t* bytes, std::size_t count) {
  static const char digits[] = "0123456789abcdef";
  std::string out(count * 2, '0');
  for (std::size_t i = 0; i < count; ++i) {
    out[2 * i] = digits[bytes[i] >> 4];
    out[2 * i + 1] = digits[bytes[i] & 15];
  }
  return out;
}

bool is_disk_failure(int code) {
  return code == ENOSPC || code == EDQUOT || code == EROFS || code == EIO;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  // A few attempts: remove_stale_temporaries may take a temporary in the instant between its
  // creation and its lock.
  constexpr int kAttempts = 4;
  for (int attempt = 1;; ++attempt) {
    const std::string temporary = unique_temporary_path_of(path);
    const auto fail = [&](int code, const std::string& what) {
      ::unlink(temporary.c_str());
      throw WriteError("cannot write '" + path + "': " + what + std::strerror(code),
                       is_disk_failure(code));
    };
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
      const int code = errno;
      if (code == EEXIST && attempt < kAttempts) continue;
      throw WriteError("cannot write '" + path + "': cannot create its temporary '" + temporary +
                           "': " + std::strerror(code),
                       is_disk_failure(code));
    }
    ::flock(fd, LOCK_EX);  // released by close: held while the temporary is incomplete
    for (std::size_t done = 0; done < content.size();) {
      const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int code = errno;
        ::close(fd);
        fail(code, "");
      }
      done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0) fail(errno, "");
    if (::rename(temporary.c_str(), path.c_str()) == 0) return;
    const int code = errno;
    if (code == ENOENT && attempt < kAttempts) continue;  // taken for a killed write's: again
    fail(code, "");
  }
}

}  // namespace aief::io

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

std::string temporary_path_of(const std::string& path) {
  const std::filesystem::path file(path);
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits: stable across runs and builds
  for (const char c : file.filename().string())
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  char name[32];
  std::snprintf(name, sizeof name, ".%016llx.tmp", static_cast<unsigned long long>(hash));
  return (file.parent_path() / name).string();
}

bool is_disk_failure(int code) {
  return code == ENOSPC || code == EDQUOT || code == EROFS || code == EIO;
}

std::string unique_temporary_path_of(const std::string& path) {
  static thread_local std::mt19937_64 random{std::random_device{}() ^
                                             (static_cast<std::uint64_t>(::getpid()) << 32)};
  const std::string shared = temporary_path_of(path);  // ".<16 hex>.tmp"
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, ".%08x.tmp", static_cast<unsigned>(random()));
  return shared.substr(0, shared.size() - 4) + suffix;
}

namespace {

// ".<16 hex>.<8 hex>.tmp", as unique_temporary_path_of names them.
bool is_unique_temporary_name(const std::string& name) {
  const auto hex = [&](std::size_t from, std::size_t count) {
    for (std::size_t i = from; i < from + count; ++i)
      if (!std::isxdigit(static_cast<unsigned char>(name[i]))) return false;
    return true;
  };
  return name.size() == 30 && name[0] == '.' && hex(1, 16) && name[17] == '.' && hex(18, 8) &&
         name.compare(26, 4, ".tmp") == 0;
}

}  // namespace

int remove_stale_temporaries(const std::string& folder) {
  int removed = 0;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!is_unique_temporary_name(name) || !it->is_regular_file(ec)) continue;
    const int fd = ::open(it->path().c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) continue;
    // A writer holds its temporary locked: only an unlocked one is a killed write's. One created
    // but not yet locked may be removed; its writer then sees its rename fail and writes again.
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::unlink(it->path().c_str()) == 0) ++removed;
    ::close(fd);
  }
  return removed;
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

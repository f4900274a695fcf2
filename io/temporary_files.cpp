#include "io/temporary_files.hpp"

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "aief/error.hpp"

namespace aief::io {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kHashDigits = 16, kRandomDigits = 8;

std::string hash_of_name(const fs::path& file) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits: stable across runs and builds
  for (const char c : file.filename().string())
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  char digits[kHashDigits + 1];
  std::snprintf(digits, sizeof digits, "%016llx", static_cast<unsigned long long>(hash));
  return digits;
}

bool hex_digits(const std::string& name, std::size_t from, std::size_t count) {
  if (name.size() < from + count) return false;
  for (std::size_t i = from; i < from + count; ++i)
    if (!std::isxdigit(static_cast<unsigned char>(name[i]))) return false;
  return true;
}

// ".<16 hex>.<8 hex>.tmp", as unique_temporary_path_of names them.
bool is_unique_temporary_name(const std::string& name) {
  constexpr std::size_t kSize = 1 + kHashDigits + 1 + kRandomDigits + 4;
  return name.size() == kSize && name[0] == '.' && hex_digits(name, 1, kHashDigits) &&
         name[1 + kHashDigits] == '.' && hex_digits(name, 2 + kHashDigits, kRandomDigits) &&
         name.compare(kSize - 4, 4, ".tmp") == 0;
}

// Removes `file` when no writer holds it locked; true when removed.
bool remove_unless_locked(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return false;
  // Only an unlocked temporary is a killed write's. One created but not yet locked may be
  // removed; its writer then sees its rename fail and says so (or, write_file_atomically, writes
  // again).
  const bool removed = ::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::unlink(file.c_str()) == 0;
  ::close(fd);
  return removed;
}

}  // namespace

std::string temporary_path_of(const std::string& path) {
  const fs::path file(path);
  return (file.parent_path() / ("." + hash_of_name(file) + ".tmp")).string();
}

std::string lock_path_of(const std::string& path) {
  const fs::path file(path);
  return (file.parent_path() / ("." + hash_of_name(file) + ".lock")).string();
}

std::string resolved_path(const std::string& path) {
  constexpr int kMostLinks = 40;  // the kernel's own bound (ELOOP)
  std::error_code ec;
  fs::path file = fs::absolute(fs::path(path), ec);
  for (int links = 0; fs::is_symlink(fs::symlink_status(file, ec)); ++links) {
    if (links == kMostLinks)
      throw Error("cannot open '" + path + "': too many levels of symbolic links");
    const fs::path target = fs::read_symlink(file, ec);
    if (ec) break;
    file = target.is_absolute() ? target : file.parent_path() / target;
  }
  const fs::path folder = fs::weakly_canonical(file.parent_path(), ec);
  return ((ec ? file.parent_path() : folder) / file.filename()).string();
}

std::string unique_temporary_path_of(const std::string& path) {
  static thread_local std::mt19937_64 random{std::random_device{}() ^
                                             (static_cast<std::uint64_t>(::getpid()) << 32)};
  const fs::path file(path);
  char suffix[kRandomDigits + 1];
  std::snprintf(suffix, sizeof suffix, "%08x", static_cast<unsigned>(random()));
  return (file.parent_path() / ("." + hash_of_name(file) + "." + suffix + ".tmp")).string();
}

int remove_stale_temporaries(const std::string& folder) {
  int removed = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (is_unique_temporary_name(it->path().filename().string()) && it->is_regular_file(ec) &&
        remove_unless_locked(it->path()))
      ++removed;
  }
  return removed;
}

int remove_stale_temporaries_of(const std::string& path) {
  const fs::path file(path);
  const std::string prefix = "." + hash_of_name(file) + ".";
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  const std::string journal = "-journal";
  int removed = 0;
  std::error_code ec;
  std::vector<fs::path> journals;
  for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0 || !it->is_regular_file(ec)) continue;
    const bool shared = name == prefix.substr(0, prefix.size() - 1) + ".tmp";
    if (is_unique_temporary_name(name) || shared) {
      removed += remove_unless_locked(it->path());
    } else if (name.size() > journal.size() &&
               name.compare(name.size() - journal.size(), journal.size(), journal) == 0) {
      journals.push_back(it->path());
    }
  }
  // A journal belongs to the database beside it: stale once that database is gone.
  for (const fs::path& j : journals) {
    const std::string owner = j.string().substr(0, j.string().size() - journal.size());
    if (!fs::exists(owner, ec) && fs::remove(j, ec)) ++removed;
  }
  return removed;
}

LockedTemporary::LockedTemporary(const std::string& path) : output_(path) {
  constexpr int kAttempts = 4;  // a name another writer drew at the same instant: draw again
  for (int attempt = 1;; ++attempt) {
    temporary_ = unique_temporary_path_of(path);
    descriptor_ = ::open(temporary_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor_ >= 0) break;
    const int code = errno;
    if (code == EEXIST && attempt < kAttempts) continue;
    throw Error("cannot write '" + path + "': cannot create its temporary '" + temporary_ +
                "': " + std::strerror(code));
  }
  ::flock(descriptor_, LOCK_EX);
}

LockedTemporary::~LockedTemporary() {
  if (!renamed_) ::unlink(temporary_.c_str());
  ::close(descriptor_);
}

bool LockedTemporary::rename_unless_output_exists() {
  if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, output_.c_str(), RENAME_NOREPLACE) == 0) {
    renamed_ = true;
    return true;
  }
  if (errno == EEXIST) return false;
  if (errno == EINVAL) {  // a file system without RENAME_NOREPLACE: check, then rename
    std::error_code ec;
    if (fs::exists(output_, ec)) return false;
    if (::rename(temporary_.c_str(), output_.c_str()) == 0) return renamed_ = true;
  }
  throw Error("cannot write '" + output_ + "': " + std::strerror(errno));
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
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
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

#include "io/output_lock.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <set>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/temporary_files.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_unwritable.hpp"
#endif

namespace aief::io {

namespace {

namespace fs = std::filesystem;

// The setting that writes without the lock, and whether it is set.
constexpr const char* kSetting = "AIEF_FILE_LOCKING";
bool locking_turned_off() {
  const char* value = std::getenv(kSetting);
  if (!value) return false;
  const std::string text(value);
  return text == "FALSE" || text == "false" || text == "0" || text == "OFF" || text == "off";
}

// The locks this process holds, by lock file: a process's second fcntl lock on one file would
// either wait for itself (open file description locks) or be granted and then dropped with the
// first's descriptor (POSIX record locks).
std::mutex held_mutex;
std::set<std::string>& held() {
  static std::set<std::string> paths;
  return paths;
}

// Takes a write lock on the whole of `fd`: an open file description lock, or a POSIX record lock
// where the kernel has none (EINVAL). Returns 0 or the errno.
int lock(int fd, bool wait) {
  struct flock whole {};
  whole.l_type = F_WRLCK;
  whole.l_whence = SEEK_SET;
  for (;;) {
    if (::fcntl(fd, wait ? F_OFD_SETLKW : F_OFD_SETLK, &whole) == 0) return 0;
    if (errno == EINTR) continue;
    if (errno != EINVAL) return errno;
    if (::fcntl(fd, wait ? F_SETLKW : F_SETLK, &whole) == 0) return 0;
    if (errno != EINTR) return errno;
  }
}

// "process 123 on host n01", as the lock file records its holder.
std::string holder_of(int fd) {
  char text[256] = {};
  const ssize_t got = ::pread(fd, text, sizeof text - 1, 0);
  std::string holder(text, got > 0 ? static_cast<std::size_t>(got) : 0);
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
  return holder.empty() ? "another process" : holder;
}

void record_holder(int fd) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string holder =
      "process " + std::to_string(::getpid()) + " on host " + std::string(host) + "\n";
  if (::ftruncate(fd, 0) == 0) {
    [[maybe_unused]] const ssize_t wrote = ::pwrite(fd, holder.data(), holder.size(), 0);
  }
}

// Whether `fd` is still the file named `path` (a holder that gave up its lock removed the file; a
// lock on that removed file locks nothing).
bool still_named(int fd, const std::string& path) {
  struct stat open_file {
  }, named{};
  return ::fstat(fd, &open_file) == 0 && ::stat(path.c_str(), &named) == 0 &&
         open_file.st_dev == named.st_dev && open_file.st_ino == named.st_ino;
}

}  // namespace

OutputLock::OutputLock(const std::string& output)
    : output_(output), lock_path_(lock_path_of(output)) {
  if (locking_turned_off()) return;
  std::error_code ec;
  fs::path absolute = fs::absolute(lock_path_, ec);
  key_ = (fs::weakly_canonical(absolute.parent_path(), ec) / absolute.filename()).string();
  {
    const std::lock_guard<std::mutex> guard(held_mutex);
    if (!held().insert(key_).second)
      throw Error("cannot write '" + output_ +
                  "': this process has it open for writing already (close the other "
                  "FeaturesFile or writer of it first)");
  }
  try {
    for (bool noted = false;;) {
      descriptor_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      const bool created = descriptor_ >= 0;
      if (!created && errno == EEXIST) descriptor_ = ::open(lock_path_.c_str(), O_RDWR | O_CLOEXEC);
      if (descriptor_ < 0) {
        const int code = errno;
        const fs::path folder = fs::path(output_).parent_path();
        if (code == ENOENT && !folder.empty() && !fs::is_directory(folder, ec))
          throw Error("cannot create '" + output_ + "': the folder '" + folder.string() +
                      "' does not exist");
        // A folder that takes no new file takes no output either: the setting would not help.
        const bool no_new_file = code == EROFS || code == EACCES || code == EPERM;
#ifdef AIEF_HAVE_HDF5
        // A whole file where no lock file can be made: say why it cannot be written and that the
        // file is fine, as opening it for writing would (io/hdf5_unwritable.hpp).
        if (no_new_file && fs::exists(output_, ec))
          if (const std::string whole = whole_file_not_writable(output_, ""); !whole.empty())
            throw Error(whole);
#endif
        throw Error("cannot write '" + output_ + "': cannot create its lock file '" + lock_path_ +
                    "' beside it: " + std::strerror(code) +
                    (no_new_file ? std::string()
                                 : " (a writer locks its output so that no other run writes it at "
                                   "the same time; " +
                                       std::string(kSetting) +
                                       "=FALSE writes without the lock when no other run can)"));
      }
      int code = lock(descriptor_, false);
      if (code == EAGAIN || code == EACCES) {
        if (!noted)
          std::cerr << "aief: note: waiting for " << holder_of(descriptor_)
                    << ", which is writing '" << output_ << "' (its lock file: '" << lock_path_
                    << "')\n";
        noted = true;
        code = lock(descriptor_, true);
      }
      if (code != 0 && created) ::unlink(lock_path_.c_str());  // nobody else locks it either
      if (code != 0)
        throw Error("cannot write '" + output_ + "': no lock can be had on its lock file '" +
                    lock_path_ + "' (fcntl: " + std::strerror(code) +
                    "): the file system gives no locks, and two runs writing one HDF5 file at "
                    "once damage it (libhdf5's own lock, flock, is missing there too or turned "
                    "off by HDF5_USE_FILE_LOCKING=FALSE). Mount it with locks (Lustre: -o flock), "
                    "write to a local disk, or, when no other run can write this file, set " +
                    kSetting + "=FALSE; nothing was written");
      if (still_named(descriptor_, lock_path_)) break;
      ::close(std::exchange(descriptor_, -1));  // its holder removed it meanwhile: lock anew
    }
    record_holder(descriptor_);
  } catch (...) {
    if (descriptor_ >= 0) ::close(descriptor_);
    const std::lock_guard<std::mutex> guard(held_mutex);
    held().erase(key_);
    throw;
  }
}

OutputLock::~OutputLock() {
  if (descriptor_ < 0) return;
  // Removed while still held: a writer waiting on it then finds it gone and locks a new one.
  ::unlink(lock_path_.c_str());
  ::close(descriptor_);
  const std::lock_guard<std::mutex> guard(held_mutex);
  held().erase(key_);
}

}  // namespace aief::io

#include "io/lock_file.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "aief/error.hpp"

namespace aief::io::lock_file {

namespace {

// A holder's line is short ("process 123 on host n01\n"); a longer file is no lock file of ours.
constexpr off_t kLongestRecord = 512;
constexpr const char kRecordStart[] = "process ";

// Why the open file `fd` at `path` is not a lock file this code made, "" when it is one.
std::string not_a_lock_file(int fd) {
  struct stat status {};
  if (::fstat(fd, &status) != 0) return std::strerror(errno);
  if (!S_ISREG(status.st_mode)) return "it is not a regular file";
  if (status.st_nlink != 1)
    return "it has " + std::to_string(status.st_nlink) + " names (a hard link to another file)";
  if (status.st_size > kLongestRecord)
    return "it holds " + std::to_string(status.st_size) + " bytes, no holder's line";
  char text[sizeof kRecordStart - 1] = {};
  const ssize_t got = ::pread(fd, text, sizeof text, 0);
  if (got > 0 && (static_cast<std::size_t>(got) < sizeof text ||
                  std::memcmp(text, kRecordStart, sizeof text) != 0))
    return "it holds something else than a holder's line";
  return "";
}

[[noreturn]] void refuse(const std::string& path, const std::string& output,
                         const std::string& why) {
  throw Error("cannot open '" + output + "': the name of its lock file, '" + path +
              "', is taken by something that is not aief's lock file (" + why +
              "); it was left untouched: remove or rename it (rm '" + path +
              "') if nothing of yours is there, then run this again");
}

}  // namespace

int open_lock_file(const std::string& path, const std::string& output, bool create, bool read_only,
                   Found& found) {
  // O_NOFOLLOW: a link planted at the lock path is refused (ELOOP), never opened; O_NONBLOCK: a
  // FIFO planted there does not hang the open.
  const int flags = (read_only ? O_RDONLY : O_RDWR) | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC;
  int fd = create ? ::open(path.c_str(), flags | O_CREAT | O_EXCL, 0666) : -1;
  found = Found::created;
  if (fd < 0 && (!create || errno == EEXIST)) {
    fd = ::open(path.c_str(), flags);
    found = Found::existing;
  }
  if (fd < 0) {
    const int code = errno;
    if (code == ELOOP) refuse(path, output, "it is a symbolic link");
    if (code == EISDIR) refuse(path, output, "it is a folder");
    if (code == ENOENT) found = Found::missing;
    errno = code;
    return -1;
  }
  if (found == Found::existing)
    if (const std::string why = not_a_lock_file(fd); !why.empty()) {
      ::close(fd);
      refuse(path, output, why);
    }
  return fd;
}

int take(int fd, short type, bool wait) {
  struct flock whole {};
  whole.l_type = type;
  whole.l_whence = SEEK_SET;
  for (;;) {
    if (::fcntl(fd, wait ? F_OFD_SETLKW : F_OFD_SETLK, &whole) == 0) return 0;
    if (errno == EINTR) continue;
    if (errno != EINVAL) return errno;
    if (::fcntl(fd, wait ? F_SETLKW : F_SETLK, &whole) == 0) return 0;
    if (errno != EINTR) return errno;
  }
}

short blocking_lock(int fd, short type) {
  struct flock probe {};
  probe.l_type = type;
  probe.l_whence = SEEK_SET;
  if (::fcntl(fd, F_OFD_GETLK, &probe) != 0) {
    probe = {};
    probe.l_type = type;
    probe.l_whence = SEEK_SET;
    if (::fcntl(fd, F_GETLK, &probe) != 0) return F_UNLCK;
  }
  return probe.l_type;
}

std::string recorded_holder(int fd) {
  char text[kLongestRecord + 1] = {};
  const ssize_t got = ::pread(fd, text, kLongestRecord, 0);
  std::string holder(text, got > 0 ? static_cast<std::size_t>(got) : 0);
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
  return holder.rfind(kRecordStart, 0) == 0 ? holder : "";
}

std::string holder_of(int fd) {
  const std::string holder = recorded_holder(fd);
  return holder.empty() ? "another process" : holder;
}

void record_holder(int fd) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string holder =
      kRecordStart + std::to_string(::getpid()) + " on host " + std::string(host) + "\n";
  if (::ftruncate(fd, 0) == 0) {
    [[maybe_unused]] const ssize_t wrote = ::pwrite(fd, holder.data(), holder.size(), 0);
  }
}

bool still_named(int fd, const std::string& path) {
  struct stat open_file {
  }, named{};
  return ::fstat(fd, &open_file) == 0 && ::lstat(path.c_str(), &named) == 0 &&
         open_file.st_dev == named.st_dev && open_file.st_ino == named.st_ino;
}

bool means_no_locks(int code) { return code != EAGAIN && code != EACCES && code != 0; }

}  // namespace aief::io::lock_file

#include "io/output_lock.hpp"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/lock_file.hpp"
#include "io/temporary_files.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_unwritable.hpp"
#endif

namespace aief::io {

namespace {

namespace fs = std::filesystem;
using lock_file::Found;

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
// first's descriptor (POSIX record locks). Writers' in `written`, readers' counted in `read`.
std::mutex held_mutex;
std::set<std::string>& written() {
  static std::set<std::string> paths;
  return paths;
}
std::map<std::string, int>& read() {
  static std::map<std::string, int> counts;
  return counts;
}

// Says once that this run waits, and for whom: a writer (its lock file names it) or readers.
void note_waiting(int fd, const std::string& output, const std::string& lock_path, bool& noted) {
  if (noted) return;
  noted = true;
  if (lock_file::blocking_lock(fd, F_WRLCK) == F_RDLCK)
    std::cerr << "aief: note: waiting while another process reads '" << output
              << "' (its lock file: '" << lock_path << "')\n";
  else
    std::cerr << "aief: note: waiting for " << lock_file::holder_of(fd) << ", which is writing '"
              << output << "' (its lock file: '" << lock_path << "')\n";
}

[[noreturn]] void refuse_without_locks(const std::string& output, const std::string& lock_path,
                                       int code) {
  throw Error("cannot write '" + output + "': no lock can be had on its lock file '" + lock_path +
              "' (fcntl: " + std::strerror(code) +
              "): the file system gives no locks, and two runs writing one HDF5 file at once "
              "damage it. Mount it with locks (Lustre: -o flock), write to a local disk, or, when "
              "no other run can write this file, set " +
              kSetting +
              "=FALSE and HDF5_USE_FILE_LOCKING=FALSE (libhdf5's own lock, flock, fails there "
              "too); nothing was written");
}

std::string owner_and_mode(const std::string& path) {
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return "";
  char mode[8];
  std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(status.st_mode & 0777));
  return "owner uid " + std::to_string(status.st_uid) + ", mode " + mode;
}

// The lock file exists but this user cannot open it for writing (another user's, made without
// group write: an older aief, or a umask of 022). Waits while its holder writes; removes it when
// nobody holds it (a killed run's) and the folder allows, else refuses naming it as removable.
void wait_for_or_remove_unwritable(const std::string& output, const std::string& lock_path,
                                   bool& noted) {
  Found found;
  const int fd = lock_file::open_lock_file(lock_path, output, false, true, found);
  if (fd < 0 && found == Found::missing) return;  // its holder removed it meanwhile
  const std::string owner = owner_and_mode(lock_path);
  if (fd < 0)
    throw Error("cannot write '" + output + "': its lock file '" + lock_path +
                "' belongs to another user (" + owner + ") who alone can read it: if no run of " +
                "theirs writes '" + output + "' now, it is stale and can be removed (rm -f '" +
                lock_path + "', as its owner), then run this again");
  const short blocking = lock_file::blocking_lock(fd, F_WRLCK);
  if (blocking == F_UNLCK) {
    // Held by nobody. A shared lock while it is removed keeps a newcomer's write lock off it; one
    // that opened it before the removal finds it unnamed once locked, and locks anew.
    const int code = lock_file::take(fd, F_RDLCK, false);
    if (code != 0 && lock_file::means_no_locks(code)) {
      ::close(fd);
      refuse_without_locks(output, lock_path, code);
    }
    if (code == 0 && lock_file::still_named(fd, lock_path) && ::unlink(lock_path.c_str()) == 0) {
      ::close(fd);
      return;
    }
    const int why = errno;
    const std::string holder = lock_file::holder_of(fd);
    ::close(fd);
    if (code != 0) return;  // locked meanwhile: look again
    throw Error("cannot write '" + output + "': its lock file '" + lock_path +
                "' was left by a run that has ended (" + holder +
                ", which holds it no more) and belongs to another user (" + owner +
                "), so this run can neither lock it nor remove it (" + std::strerror(why) +
                "): it is stale and can be removed: rm -f '" + lock_path +
                "' (as its owner, or the folder's), then run this again");
  }
  note_waiting(fd, output, lock_path, noted);
  if (blocking == F_WRLCK)
    lock_file::take(fd, F_RDLCK, true);  // until that writer ends
  else
    std::this_thread::sleep_for(std::chrono::seconds(1));  // readers share: look again
  ::close(fd);
}

// Why the lock file could not be made (`code`, the errno of its creation): the sentence to throw.
std::string cannot_make(const std::string& output, const std::string& lock_path, int code) {
  std::error_code ec;
  const fs::path folder = fs::path(lock_path).parent_path();
  if (code == ENOENT && !fs::is_directory(folder, ec))
    return "cannot create '" + output + "': the folder '" +
           fs::path(output).parent_path().string() + "' does not exist";
  // A folder that takes no new file takes no output either: the setting would not help.
  const bool no_new_file = code == EROFS || code == EACCES || code == EPERM;
  if (no_new_file && fs::exists(output, ec)) {
    if (::access(output.c_str(), W_OK) == 0)
      return "cannot write '" + output + "' in place: its lock file '" + lock_path +
             "' cannot be made in the folder '" + folder.string() + "' (" + std::strerror(code) +
             "), though the file itself is writable (a writer locks its output with a file "
             "beside it). To write it in place when no other run writes it, set " +
             kSetting +
             "=FALSE (a merge, which writes a new file beside its output, cannot); or copy it "
             "to a folder you can write to and write it there; nothing was written";
#ifdef AIEF_HAVE_HDF5
    // A whole file that cannot be written: say why and that the file is fine, as opening it for
    // writing would (io/hdf5_unwritable.hpp).
    if (const std::string whole = whole_file_not_writable(output, ""); !whole.empty()) return whole;
#endif
  }
  return "cannot write '" + output + "': cannot create its lock file '" + lock_path +
         "' beside it: " + std::strerror(code) +
         (no_new_file ? std::string()
                      : " (a writer locks its output so that no other run writes it at the same "
                        "time; " +
                            std::string(kSetting) +
                            "=FALSE writes without the lock when no other "
                            "run can)");
}

}  // namespace

OutputLock::OutputLock(const std::string& output)
    : output_(output), lock_path_(lock_path_of(resolved_path(output))) {
  if (locking_turned_off()) return;
  {
    const std::lock_guard<std::mutex> guard(held_mutex);
    if (read().count(lock_path_))
      throw Error("cannot open '" + output_ +
                  "' for writing: another handle holds it open (a reader of it in this process: "
                  "close that one first); the file itself is whole and was left as it was");
    if (!written().insert(lock_path_).second)
      throw Error("cannot write '" + output_ +
                  "': this process has it open for writing already (close the other "
                  "FeaturesFile or writer of it first)");
  }
  try {
    for (bool noted = false;;) {
      Found found;
      descriptor_ = lock_file::open_lock_file(lock_path_, output_, true, false, found);
      if (descriptor_ < 0) {
        const int code = errno;
        std::error_code ec;
        if (found == Found::existing && code == EACCES) {
          wait_for_or_remove_unwritable(output_, lock_path_, noted);
          continue;
        }
        if (found == Found::missing && fs::is_directory(fs::path(lock_path_).parent_path(), ec))
          continue;  // removed by its holder between the two opens
        throw Error(cannot_make(output_, lock_path_, code));
      }
      int code = lock_file::take(descriptor_, F_WRLCK, false);
      if (code == EAGAIN || code == EACCES) {
        note_waiting(descriptor_, output_, lock_path_, noted);
        code = lock_file::take(descriptor_, F_WRLCK, true);
      }
      if (code != 0 && found == Found::created)
        ::unlink(lock_path_.c_str());  // nobody else locks it either
      if (code != 0) refuse_without_locks(output_, lock_path_, code);
      if (lock_file::still_named(descriptor_, lock_path_)) break;
      ::close(std::exchange(descriptor_, -1));  // its holder removed it meanwhile: lock anew
    }
    lock_file::record_holder(descriptor_);
  } catch (...) {
    if (descriptor_ >= 0) ::close(descriptor_);
    const std::lock_guard<std::mutex> guard(held_mutex);
    written().erase(lock_path_);
    throw;
  }
}

OutputLock::~OutputLock() {
  if (descriptor_ < 0) return;
  // Removed while still held: a writer waiting on it then finds it gone and locks a new one.
  ::unlink(lock_path_.c_str());
  ::close(descriptor_);
  const std::lock_guard<std::mutex> guard(held_mutex);
  written().erase(lock_path_);
}

ReadLock::ReadLock(const std::string& file) {
  if (locking_turned_off()) return;
  lock_path_ = lock_path_of(resolved_path(file));
  {
    const std::lock_guard<std::mutex> guard(held_mutex);
    if (written().count(lock_path_)) return;  // this process writes it: its reads are its own
  }
  // A few tries: a lock file removed by its holder as this reader locked it is looked up again.
  constexpr int kTries = 8;
  for (int attempt = 0; attempt < kTries; ++attempt) {
    // Made when missing, so that a writer that comes while this reads waits; a folder that takes
    // no new file takes no writer either, and is read without a lock.
    Found found;
    bool writable = true;
    int fd = lock_file::open_lock_file(lock_path_, file, true, false, found);
    if (fd < 0 && found == Found::existing && errno == EACCES) {  // another user's, 0644
      writable = false;
      fd = lock_file::open_lock_file(lock_path_, file, false, true, found);
    }
    if (fd < 0 && found == Found::missing && attempt + 1 < kTries) continue;
    if (fd < 0) return;
    const int code = lock_file::take(fd, F_RDLCK, false);
    if (code == 0 && lock_file::still_named(fd, lock_path_)) {
      descriptor_ = fd;
      removable_ = writable;
      const std::lock_guard<std::mutex> guard(held_mutex);
      ++read()[lock_path_];
      return;
    }
    if ((code == EAGAIN || code == EACCES) && lock_file::recorded_holder(fd).empty()) {
      // No writer recorded: a reader that is removing the lock file as it ends (~ReadLock, a
      // write lock held from its taking to the close), or a writer in the instant before it
      // records itself. Wait for it and look again, rather than call a file nobody writes locked.
      lock_file::take(fd, F_RDLCK, true);
      ::close(fd);
      continue;
    }
    if (code == EAGAIN || code == EACCES) {
      const std::string holder = lock_file::holder_of(fd);
      ::close(fd);
      throw Error("cannot open '" + file + "': it is locked by a writer, " + holder +
                  " (its lock file: '" + lock_path_ +
                  "'; another aief still writing it? wait until that run ends, then run this "
                  "again)");
    }
    if (code != 0 && found == Found::created) ::unlink(lock_path_.c_str());
    ::close(fd);
    if (code != 0) return;  // the file system gives no locks: no writer holds one either
  }
}

ReadLock::~ReadLock() {
  if (descriptor_ < 0) return;
  // The last reader removes the lock file, as a writer does: only while no other process holds
  // a lock on it (its own turned into a writer's), so a waiting writer then locks a new one.
  if (removable_ && lock_file::take(descriptor_, F_WRLCK, false) == 0 &&
      lock_file::still_named(descriptor_, lock_path_))
    ::unlink(lock_path_.c_str());
  ::close(descriptor_);
  const std::lock_guard<std::mutex> guard(held_mutex);
  if (--read()[lock_path_] == 0) read().erase(lock_path_);
}

}  // namespace aief::io

#pragma once
// The lock file beside an output (io/output_lock.hpp) and the fcntl locks on it: how it is opened
// (never through a link, never another file: a lock path is a name anyone in the folder can
// plant), what it records of its holder, and how a lock is taken and probed.
#include <string>

namespace aief::io::lock_file {

// How open_lock_file found the lock path.
enum class Found { created, existing, missing };

// Opens the lock file `path` (of the output `output`, for messages) for reading and writing,
// creating it when `create` (mode 0666 less the umask, so that a group folder's members with
// umask 002 can all lock it). Never follows a link and never opens anything but a file this
// code makes (regular, one name, empty or holding a holder's line): anything else is refused
// with aief::Error naming it and how to remove it. `read_only`: opened for reading only (a
// reader's shared lock, or a lock file another user made without group write). Returns -1 with
// errno set when the system refuses the open (found: missing for ENOENT).
int open_lock_file(const std::string& path, const std::string& output, bool create, bool read_only,
                   Found& found);

// Takes a lock of `type` (F_RDLCK, F_WRLCK) on the whole of `fd`: an open file description lock,
// or a POSIX record lock where the kernel has none (EINVAL). Returns 0 or the errno.
int take(int fd, short type, bool wait);

// The type of the lock that keeps a lock of `type` from `fd` (F_RDLCK, F_WRLCK), F_UNLCK when
// none does.
short blocking_lock(int fd, short type);

// "process 123 on host n01", as the lock file records its writer (once it holds the lock); ""
// when it records none.
std::string recorded_holder(int fd);
// The same, "another process" when it records none.
std::string holder_of(int fd);
void record_holder(int fd);

// Whether `fd` is still the file named `path` (a holder that gave up its lock removed the file; a
// lock on that removed file locks nothing).
bool still_named(int fd, const std::string& path);

// Whether the errno of a lock request says the file system gives no locks.
bool means_no_locks(int code);

}  // namespace aief::io::lock_file

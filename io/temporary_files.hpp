#pragma once
// The temporaries beside an output that every writer of io/ goes through: a write goes to a file
// of its own beside the output, renamed over it only when whole. Names are hidden, short (any
// legal file name has one: name + ".tmp" would pass NAME_MAX for a name of 252 bytes or more)
// and never end in an output extension, so a temporary is no output's name and no image's.
#include <string>

#include "aief/error.hpp"

namespace aief::io {

// The temporary of one write of `path`: "." + the 16 hex digits of a hash of the file name +
// "." + 8 random hex digits + ".tmp", beside it. Two processes writing the same output (a batch
// resubmitted while the first still runs, two merges into one file) each have their own.
std::string unique_temporary_path_of(const std::string& path);

// Removes, below `folder`, temporaries as unique_temporary_path_of names them that no writer
// holds locked: a killed write's. A write in progress holds its own (flock: write_file_atomically
// and LockedTemporary take it, libhdf5 takes it on every file it has open for writing). Returns
// how many it removed.
int remove_stale_temporaries(const std::string& folder);

// The same for the temporaries of the one output `path` only, beside it: those of a killed run of
// any writer, with the journal SQLite leaves beside a killed COLMAP export's, and the shared-name
// temporary (temporary_path_of) of an older aief. Returns how many it removed.
int remove_stale_temporaries_of(const std::string& path);

// The shared-name temporary older aief versions used beside `path`: "." + 16 hex digits of a
// hash of the file name + ".tmp", the same for the same path; removed as stale, never written.
std::string temporary_path_of(const std::string& path);

// The lock file of `path` (io/output_lock.hpp): "." + the 16 hex digits of a hash of the file
// name + ".lock", beside it. OutputLock takes it of resolved_path(path).
std::string lock_path_of(const std::string& path);

// The file `path` names: symbolic links of its last component followed (a missing target too:
// the file a write through the link creates), its folder made absolute and canonical. Two names
// of one file (a link and its target, "./x.h5" and "x.h5") give one path, so one lock and one
// place where a write renames its temporary (never over the link). Throws aief::Error for a
// loop of links.
std::string resolved_path(const std::string& path);

// A unique temporary beside `path`, created exclusively and locked for as long as this object
// lives (for writers that reopen the file by name, as SQLite does: its fcntl locks are not
// flock's, so they do not clash). Removed on destruction unless renamed over its output.
class LockedTemporary {
 public:
  // Throws Error naming `path` when the folder does not take a new file.
  explicit LockedTemporary(const std::string& path);
  ~LockedTemporary();
  LockedTemporary(const LockedTemporary&) = delete;
  LockedTemporary& operator=(const LockedTemporary&) = delete;

  const std::string& path() const { return temporary_; }

  // Renames the temporary to `path` unless `path` exists (then returns false and keeps it).
  // Throws Error with the system's reason on any other failure.
  bool rename_unless_output_exists();

 private:
  std::string output_, temporary_;
  int descriptor_ = -1;
  bool renamed_ = false;
};

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

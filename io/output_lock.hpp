#pragma once
// aief's own lock on an output that one run writes in place or replaces (the HDF5 writers:
// extract --batch --format h5, match --pairs, merge, aief.FeaturesFile), held for the whole run.
//
// libhdf5's own lock is flock, which cluster file systems often lack (Lustre mounted without
// -o flock answers ENOSYS) and which HDF5_USE_FILE_LOCKING=FALSE, the usual setting there, turns
// off: two runs then wrote one file at once and damaged it. This lock does not depend on either:
// an fcntl lock (open file description lock, else a POSIX record lock) on a lock file beside the
// file the output's name resolves to (io/temporary_files.hpp: resolved_path, so a link and its
// target share one lock), "." + 16 hex digits of a hash of its name + ".lock" (lock_path_of),
// which NFS (NLM, NFSv4), Lustre (-o flock) and GPFS hold across nodes. The kernel (or the lock
// server) drops it when its process dies, so a killed run's lock never stays; the file itself
// is removed when the lock is given up (a kill -9 leaves it, unlocked, for the next run). The
// lock file is opened without following links and only when it is one aief made
// (io/lock_file.hpp), with the umask's mode: a group folder's members share it. One left by
// another user without group write, and held by nobody, is removed when the folder allows, else
// named with the command that removes it.
//
// A second writer waits for the first to end (a note on stderr names the file and the first
// writer's process and host), then sees what the first wrote: a resubmitted batch finds its images
// done, a second merge adds its shards to the first's output. When no lock can be had (the
// file system refuses fcntl locks), the write is refused, naming the file, the reason and the
// settings AIEF_FILE_LOCKING=FALSE and HDF5_USE_FILE_LOCKING=FALSE, which write without either
// lock when the user knows that no other run writes the file.
//
// A reader (ReadLock: merge's inputs, colmap, match --pairs' features) takes a shared lock on the
// lock file (made when missing, where the folder allows, and removed by the last reader): a file a
// writer holds is refused, as libhdf5's own lock refuses it, and a writer that comes while it
// reads waits ("waiting while another process reads").
#include <string>

namespace aief::io {

class OutputLock {
 public:
  // Takes the lock of `output`, waiting while another process holds it (or reads it). Throws
  // aief::Error when no lock can be had, when its lock path holds something else than aief's lock
  // file, or when this process already holds it or reads it (a file opened twice).
  explicit OutputLock(const std::string& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string output_, lock_path_;
  int descriptor_ = -1;  // -1: AIEF_FILE_LOCKING=FALSE, no lock taken
};

class ReadLock {
 public:
  // Takes a shared lock on the lock file of `file`. Throws aief::Error when a writer holds it,
  // naming the writer; waits for a lock that records no writer (a reader removing the lock file
  // as it ends). Takes none, silently, where the folder takes no lock file, the file system
  // gives no locks, AIEF_FILE_LOCKING=FALSE is set, or this process writes the file itself.
  explicit ReadLock(const std::string& file);
  ~ReadLock();
  ReadLock(const ReadLock&) = delete;
  ReadLock& operator=(const ReadLock&) = delete;

 private:
  std::string lock_path_;
  int descriptor_ = -1;     // -1: no lock file, or no lock taken
  bool removable_ = false;  // opened for writing: the last reader removes the lock file
};

}  // namespace aief::io

#pragma once
// aief's own lock on an output that one run writes in place or replaces (the HDF5 writers:
// extract --batch --format h5, match --pairs, merge, aief.FeaturesFile), held for the whole run.
//
// libhdf5's own lock is flock, which cluster file systems often lack (Lustre mounted without
// -o flock answers ENOSYS) and which HDF5_USE_FILE_LOCKING=FALSE, the usual setting there, turns
// off: two runs then wrote one file at once and damaged it. This lock does not depend on either:
// an fcntl lock (open file description lock, else a POSIX record lock) on a lock file beside the
// output, "." + 16 hex digits of a hash of the output's name + ".lock" (io/temporary_files.hpp:
// lock_path_of),
// which NFS (NLM, NFSv4), Lustre (-o flock) and GPFS hold across nodes. The kernel (or the lock
// server) drops it when its process dies, so a killed run's lock never stays; the file itself
// is removed when the lock is given up (a kill -9 leaves it, unlocked, for the next run).
//
// A second writer waits for the first to end (a note on stderr names the file and the first
// writer's process and host), then sees what the first wrote: a resubmitted batch finds its images
// done, a second merge adds its shards to the first's output. When no lock can be had (the
// file system refuses fcntl locks), the write is refused, naming the file, the reason and the
// setting AIEF_FILE_LOCKING=FALSE, which writes without the lock when the user knows that no
// other run writes the file.
#include <string>

namespace aief::io {

class OutputLock {
 public:
  // Takes the lock of `output`, waiting while another process holds it. Throws aief::Error when
  // no lock can be had, or when this process already holds it (a file opened twice for writing).
  explicit OutputLock(const std::string& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string output_, lock_path_, key_;
  int descriptor_ = -1;  // -1: AIEF_FILE_LOCKING=FALSE, no lock taken
};

}  // namespace aief::io

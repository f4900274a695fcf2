#pragma once
// Hdf5File::write_guarded, the one way a write reaches the file (io/hdf5_file.hpp: reserved
// before, fenced on failure, flushed in batches): for the files that define Hdf5File's writes.
#include <mutex>
#include <string>

#include "io/hdf5_file.hpp"
#include "io/hdf5_objects.hpp"

namespace aief::io {

template <class Write>
void Hdf5File::write_guarded(std::uint64_t bytes, const std::string& what, Write&& write,
                             Flush flush, bool adds_a_group) {
  hdf5::silence_hdf5();
  const std::lock_guard<std::mutex> lock(failure_mutex_);
  if (!failure_.empty())
    throw Error("cannot write " + what + " to '" + path_ + "': an earlier write failed (" +
                failure_ + ")");
  try {
    reserve(bytes + kMetadataAllowance);
  } catch (const std::exception& e) {
    // Nothing of this write happened: the writes before it are whole in memory, flushed here
    // into space reserved before them.
    failure_ = e.what();
    try {
      flush_now();
    } catch (const std::exception&) {
    }
    fence();
    throw Error("cannot write " + what + " to '" + path_ + "': " + failure_ +
                kCompleteBeforeIsKept);
  }
  try {
    write();
    written_groups_ += adds_a_group ? 1 : 0;
    // The first write is flushed at once: a run killed before its first batch keeps it.
    if (flush == Flush::now ||
        (flush == Flush::batched && (++unflushed_writes_ >= kWritesPerFlush || !flushed_a_write_)))
      flush_now();
  } catch (const std::exception& e) {
    // This write may be half done in memory, so nothing more is flushed: the file keeps what the
    // last flush wrote, and the writes since then are lost with this one.
    failure_ = e.what();
    fence();
    const int lost = written_groups_ - flushed_groups_;
    throw Error("cannot write " + what + " to '" + path_ + "': " + failure_ +
                (lost == 0 ? std::string(kCompleteBeforeIsKept)
                           : kKeepsTheFlushedWrites + std::to_string(flushed_groups_) +
                                 " writes flushed before it; the " + std::to_string(lost) +
                                 " since the last flush are lost: write them again)"));
  }
}

}  // namespace aief::io

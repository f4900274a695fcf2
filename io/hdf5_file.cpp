#include "io/hdf5_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <hdf5.h>
#include <sys/mman.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/hdf5_objects.hpp"
#include "io/hdf5_unwritable.hpp"
#include "io/json_writer.hpp"
#include "io/temporary_files.hpp"

namespace aief::io {

using namespace hdf5;

namespace {

// What another process's lock on the file means here, and what to do.
constexpr const char* kLockedByAWriter =
    "it is locked by a writer (another aief still writing it? wait until that run ends, then run "
    "this again)";

// Why `path` cannot be opened or created as an HDF5 file, in the words a user acts on: a missing
// folder, a directory, a file another process holds locked, a file that is not HDF5 or is damaged.
// Creates `path` with a first block of zeros: the system's reason when the disk cannot hold it
// (the file removed), "" otherwise, also when the file cannot be made at all (open_failure then
// says why). A disk already full is found here, before libhdf5, whose failed create keeps its
// file structures allocated.
std::string first_block_does_not_fit(const std::string& path) {
  // The umask's mode, as libhdf5 gives: a group folder's members with umask 002 share the file.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666);
  if (fd < 0) return {};
  const char block[4096] = {};
  const ssize_t wrote = ::write(fd, block, sizeof block);
  const int write_error = wrote < 0 ? errno : ENOSPC;  // a short write: no room for the rest
  ::close(fd);
  if (wrote == static_cast<ssize_t>(sizeof block)) return {};
  std::error_code ec;
  std::filesystem::remove(path, ec);
  return std::strerror(write_error);
}

std::string open_failure(const std::string& path, bool creating, const std::string& hdf5_said) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path folder = fs::path(path).parent_path();
  if (creating && !folder.empty() && !fs::is_directory(folder, ec))
    return "cannot create '" + path + "': the folder '" + folder.string() + "' does not exist";
  if (fs::is_directory(path, ec))
    return "cannot open '" + path + "' as an HDF5 file: it is a directory";
  if (hdf5_said.find("unable to lock file") != std::string::npos ||
      hdf5_said == "Resource temporarily unavailable")
    return "cannot open '" + path + "': " + kLockedByAWriter;
  // libhdf5's own lock (flock) on a file system that gives none (NFS without its lock daemon:
  // ENOLCK; Lustre without -o flock: ENOSYS): nothing is wrong with the file.
  if (hdf5_said == std::strerror(ENOLCK) || hdf5_said == std::strerror(ENOSYS)) {
    std::string said(creating ? "cannot create '" : "cannot open '");
    said.append(path).append("': libhdf5 can have no lock on it (").append(hdf5_said);
    said.append(
        "): the file system gives no locks. Set HDF5_USE_FILE_LOCKING=FALSE to open it without "
        "libhdf5's lock (aief's own lock file still keeps two aief runs from writing it at "
        "once), or mount the file system with locks");
    return said.append(creating ? "" : "; the file itself was not touched");
  }
  if (!creating && H5Fis_hdf5(path.c_str()) == 0)
    return "cannot open '" + path + "': it is not an HDF5 file";
  const int fd = ::open(path.c_str(), creating ? O_RDWR | O_CREAT | O_EXCL : O_RDONLY, 0666);
  if (fd < 0)
    return std::string("cannot ") + (creating ? "create '" : "open '") + path +
           "': " + std::strerror(errno);
  // libhdf5 names no reason when it cannot write a new file's first block (a full disk): the
  // system names it.
  const char block[4096] = {};
  const int wrote = creating ? static_cast<int>(::write(fd, block, sizeof block)) : 0;
  const int write_error = errno;
  ::close(fd);
  if (creating) {
    fs::remove(path, ec);
    if (wrote < 0) return "cannot create '" + path + "': " + std::strerror(write_error);
    return "cannot create '" + path +
           "': " + (hdf5_said.empty() ? std::string("libhdf5 could not write it") : hdf5_said);
  }
  if (std::string whole = whole_file_not_writable(path, hdf5_said); !whole.empty()) return whole;
  return damaged_file(path, hdf5_said);
}

// How aief creates files: without a free-space manager (H5F_FSPACE_STRATEGY_NONE), space freed
// during a run (a replaced group, a grown heap) is never handed out again, so no write between
// two flushes lands in space the last flushed state still refers to, and a killed run leaves a
// file as of its last flush. It also costs 5% fewer instructions a pair than the default
// manager. The strategy is recorded in the file (superblock version 2; read by libhdf5 1.10 and
// later, hence h5py and hloc).
Handle file_creation() {
  Handle creation(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  H5Pset_file_space_strategy(creation.get(), H5F_FSPACE_STRATEGY_NONE, 0, 1);
  return creation;
}

// How aief opens a file it only reads: libhdf5's metadata cache at a fixed size, grown only for an
// entry too large for it (its "flash" increase, kept: the local heap of a top-level group grows
// with the images, about 2.4 MB in a matches file of 1,000,000 pairs over 100,000 images). The
// cache counts an object header at its size on disk, not at the size of the messages decoded into
// it (about 11 to 28 times more), and by default grows to 32 MB whenever its hit rate falls below
// 90%, as it does when each group is read once: `aief colmap` over 20,000 pairs peaked at 365 MB
// so, 156 MB at 4 MB. At 1 or 2 MB, the same pairs from the 1,000,000-pair file took twice the
// wall time; at 4 MB they take no longer than from a 50,000-pair file.
constexpr std::size_t kReadCacheBytes = std::size_t{4} << 20;
// A reader going through the file once in name order (merge's two passes) reuses only the nodes of
// the group index on its path, which a small cache keeps: `aief merge` of two shards of 20,000
// images peaks at 95 MB so, 201 MB at 4 MB, for no more CPU (docs/scale_out.md).
constexpr std::size_t kInNameOrderCacheBytes = std::size_t{256} << 10;
Handle read_access(std::size_t cache_bytes) {
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5AC_cache_config_t cache{};
  cache.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Pget_mdc_config(access.get(), &cache) >= 0) {
    cache.set_initial_size = true;
    cache.initial_size = cache_bytes;
    cache.min_size = std::min<std::size_t>(cache.min_size, cache_bytes);
    cache.incr_mode = H5C_incr__off;  // the flash increase for large entries stays on
    cache.decr_mode = H5C_decr__off;
    H5Pset_mdc_config(access.get(), &cache);
  }
  return access;
}
}  // namespace

Hdf5File::Hdf5File(const std::string& path, Mode mode) : path_(path) {
  silence_hdf5();
  std::error_code ec;
  bool creating = false;
  std::string reason;  // libhdf5's, read before any other call of its API clears it
  const bool writing = mode == Mode::read_write || mode == Mode::write_temporary;
  if (mode == Mode::read_write && !std::filesystem::is_directory(path, ec))
    lock_ = std::make_unique<OutputLock>(path);
  if (!writing) {
    if (!std::filesystem::exists(path, ec)) throw Error("cannot open '" + path + "': no such file");
    read_lock_ = std::make_unique<ReadLock>(path);  // refuses a file a writer holds
    const std::size_t cache_bytes =
        mode == Mode::read_in_name_order ? kInNameOrderCacheBytes : kReadCacheBytes;
    const Handle access = read_access(cache_bytes);
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get());
    if (file_ < 0) reason = hdf5_reason();
  } else if (std::filesystem::exists(path, ec)) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (file_ < 0) reason = hdf5_reason();
  } else {
    // Created under a temporary name, renamed once its structure is on disk (flush_created_file):
    // a run killed in between leaves no file that cannot be opened.
    creating = true;
    // A temporary of its own (another run may be creating the same file): a killed run's are
    // unlocked and removed; libhdf5 holds a lock on each it has open.
    // Beside the file a link names, and renamed onto it: a write through a link never replaces
    // the link (io/temporary_files.hpp: resolved_path).
    creating_at_ = resolved_path(path);
    remove_stale_temporaries_of(creating_at_);
    creating_as_ = unique_temporary_path_of(creating_at_);
    const std::string no_room = first_block_does_not_fit(creating_as_);
    if (!no_room.empty()) throw Error("cannot create '" + path + "': " + no_room);
    const Handle creation = file_creation();
    file_ = H5Fcreate(creating_as_.c_str(), H5F_ACC_TRUNC, creation.get(), H5P_DEFAULT);
    if (file_ < 0) reason = hdf5_reason();
  }
  if (file_ < 0) {
    // libhdf5 leaves the empty file it could not initialise (a full disk): not ours to keep.
    if (creating) std::filesystem::remove(creating_as_, ec);
    throw Error(open_failure(path, creating, reason));
  }
  if (writing) {
    void* handle = nullptr;
    const Handle access(H5Fget_access_plist(file_), H5Pclose);
    if (H5Pget_driver(access.get()) == H5FD_SEC2 &&
        H5Fget_vfd_handle(file_, H5P_DEFAULT, &handle) >= 0 && handle)
      descriptor_ = *static_cast<int*>(handle);
    reserved_until_ =
        static_cast<std::uint64_t>(std::filesystem::file_size(creating ? creating_as_ : path, ec));
    const auto visit = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
      Hdf5File& file = *static_cast<Hdf5File*>(data);
      const std::string_view path(name);
      if (info->type == H5O_TYPE_GROUP) {
        file.groups_.insert(std::hash<std::string_view>{}(path));
      } else if (info->type == H5O_TYPE_DATASET) {
        if (file.first_image_.empty() && path.size() > 11 && path.ends_with("/image_size"))
          file.first_image_ = path.substr(0, path.size() - 11);
        if (path.ends_with("/matches0")) file.holds_pairs_ = true;
      }
      return 0;
    };
    if (H5Ovisit2(file_, H5_INDEX_NAME, H5_ITER_NATIVE, visit, this, H5O_INFO_BASIC) < 0) {
      const std::string reason = hdf5_reason();
      H5Fclose(std::exchange(file_, -1));
      throw Error(damaged_file(path_, reason));
    }
    groups_known_ = true;
    if (creating) flush_created_file();
  }
}

void Hdf5File::flush_created_file() {
  // Its structure on disk at once: a run killed before its first write leaves a file that opens.
  std::error_code ec;
  try {
    flush_now();
    flushed_a_write_ = false;
    // Never over a file another run created meanwhile.
    if (::renameat2(AT_FDCWD, creating_as_.c_str(), AT_FDCWD, creating_at_.c_str(),
                    RENAME_NOREPLACE) != 0 &&
        (errno != EINVAL || ::rename(creating_as_.c_str(), creating_at_.c_str()) != 0))
      throw Error(errno == EEXIST ? "another run created it at the same moment (this run wrote "
                                    "nothing to it): run this command again, which adds to "
                                    "that file"
                                  : std::strerror(errno));
  } catch (const std::exception& e) {
    fence();
    H5Fclose(std::exchange(file_, -1));
    std::filesystem::remove(creating_as_, ec);
    throw Error("cannot create '" + path_ + "': " + e.what());
  }
}

namespace {

// A group's path as H5Ovisit names it (no leading '/'), or nothing when libhdf5 would read it
// otherwise than as its plain components ("a//b", "a/./b", "a/"): such names are looked up in
// the file.
std::optional<std::string_view> plain_path(const std::string& name) {
  std::string_view path(name);
  while (!path.empty() && path.front() == '/') path.remove_prefix(1);
  std::string padded(1, '/');
  padded.append(path).push_back('/');
  if (path.empty() || padded.find("//") != std::string::npos ||
      padded.find("/./") != std::string::npos || padded.find("/../") != std::string::npos)
    return std::nullopt;
  return path;
}

}  // namespace

bool Hdf5File::may_hold(const std::string& group) const {
  if (!groups_known_) return true;
  const auto path = plain_path(group);
  return !path || groups_.count(std::hash<std::string_view>{}(*path)) > 0;
}

void Hdf5File::note_group(const std::string& group) {
  if (!groups_known_) return;
  const auto path = plain_path(group);
  if (!path) {  // from now on every name is looked up in the file
    groups_known_ = false;
    groups_.clear();
    return;
  }
  for (std::size_t at = path->find('/'); at != std::string::npos; at = path->find('/', at + 1))
    groups_.insert(std::hash<std::string_view>{}(path->substr(0, at)));
  groups_.insert(std::hash<std::string_view>{}(*path));
}

Hdf5File::~Hdf5File() {
  silence_hdf5();
  // A close whose last writes fail leaves the file open in libhdf5, which would try again (and
  // crash) at exit: the writes go to the scratch file instead, and the file is closed.
  if (file_ >= 0 && H5Fclose(file_) < 0) {
    fence();
    H5Fclose(file_);
  }
  // Give back the blocks reserved past the end that the file did not grow into.
  std::error_code ec;
  const std::uint64_t size = failure_.empty() ? std::filesystem::file_size(path_, ec) : 0;
  if (!ec && reserved_until_ > size && size > 0) {
    const int fd = ::open(path_.c_str(), O_WRONLY);
    if (fd >= 0) {
      ::fallocate(fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, static_cast<off_t>(size),
                  static_cast<off_t>(reserved_until_ - size));
      ::close(fd);
    }
  }
}

void Hdf5File::close() {
  silence_hdf5();
  if (file_ < 0) return;
  try {
    reserve(0);
  } catch (const Error& e) {
    fence();
    H5Fclose(std::exchange(file_, -1));
    throw Error("cannot close '" + path_ + "': " + e.what());
  }
  if (H5Fclose(file_) >= 0) {
    file_ = -1;
    return;
  }
  const std::string reason = hdf5_reason();
  fence();
  H5Fclose(std::exchange(file_, -1));
  throw Error("cannot close '" + path_ + "': " + reason);
}

void Hdf5File::reserve(std::uint64_t extra) {
  haddr_t end_of_allocation = 0;
  if (descriptor_ < 0 || H5Fget_eoa(file_, &end_of_allocation) < 0) return;
  const std::uint64_t until = static_cast<std::uint64_t>(end_of_allocation) + extra;
  if (until <= reserved_until_) return;
  // FALLOC_FL_KEEP_SIZE: blocks past the end, the file's size unchanged (libhdf5 checks it).
  if (::fallocate(descriptor_, FALLOC_FL_KEEP_SIZE, static_cast<off_t>(reserved_until_),
                  static_cast<off_t>(until - reserved_until_)) == 0) {
    reserved_until_ = until;
  } else if (errno != EOPNOTSUPP && errno != ENOSYS) {
    throw Error(std::strerror(errno));
  }
}

void Hdf5File::fence() {
  if (descriptor_ < 0) return;
  const int scratch = ::memfd_create("aief-hdf5-after-a-failed-write", 0);
  if (scratch >= 0) {
    ::dup2(scratch, descriptor_);
    ::close(scratch);
  }
}

void Hdf5File::flush_now() {
  reserve(0);  // everything the flush writes lies below the end of allocation
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) throw Error(hdf5_reason());
  unflushed_writes_ = 0;
  flushed_groups_ = written_groups_;
  flushed_a_write_ = true;
}

}  // namespace aief::io

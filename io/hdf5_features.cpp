#include "io/hdf5_features.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <fcntl.h>
#include <hdf5.h>
#include <sys/mman.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/json_writer.hpp"
#include "io/merge_option_check.hpp"
#include "io/option_record.hpp"

namespace aief::io {

namespace {

// One HDF5 handle, closed by its own close function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// Errors are reported by aief::Error; libhdf5's own stack printing would only repeat them. The
// setting is per thread in a thread-safe libhdf5 (a batch writes from a TBB worker), so every
// entry point calls this on its own thread.
void silence_hdf5() {
  thread_local const bool silenced = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
  (void)silenced;
}

// The reason libhdf5 gives for the last failure on this thread: the system's message when a
// read or write of the file failed ("No space left on device"), else its innermost description.
std::string hdf5_reason() {
  std::string innermost;
  const auto visit = [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
    if (error->desc) *static_cast<std::string*>(data) = error->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, visit, &innermost);
  H5Eclear2(H5E_DEFAULT);
  const std::string marker = "error message = '";
  const std::size_t at = innermost.find(marker);
  if (at != std::string::npos) {
    const std::size_t begin = at + marker.size();
    return innermost.substr(begin, innermost.find('\'', begin) - begin);
  }
  return innermost;
}

// Whether every component of `path` exists (H5Lexists fails when a parent is missing).
bool exists(hid_t file, const std::string& path) {
  silence_hdf5();
  std::size_t at = 0;
  while (true) {
    at = path.find('/', at + 1);
    const std::string prefix = path.substr(0, at);
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (at == std::string::npos) return true;
  }
}

template <class T>
hid_t native_type();
template <>
hid_t native_type<float>() {
  return H5T_NATIVE_FLOAT;
}
template <>
hid_t native_type<std::uint8_t>() {
  return H5T_NATIVE_UINT8;
}
template <>
hid_t native_type<std::int32_t>() {
  return H5T_NATIVE_INT32;
}
template <>
hid_t native_type<std::int64_t>() {
  return H5T_NATIVE_INT64;
}

// Creates and writes one dataset, closed here so that a failure of its last write (libhdf5 may
// keep small data in its sieve buffer until the close) is an error, not a silent loss.
template <class T>
void write_dataset(hid_t group, const char* name, const std::vector<hsize_t>& dims,
                   const std::vector<T>& values, const std::string& where) {
  const Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                     H5Sclose);
  const hid_t set =
      H5Dcreate2(group, name, native_type<T>(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) throw Error(hdf5_reason() + " (creating '" + where + "/" + name + "')");
  const bool written = values.empty() || H5Dwrite(set, native_type<T>(), H5S_ALL, H5S_ALL,
                                                  H5P_DEFAULT, values.data()) >= 0;
  const bool closed = H5Dclose(set) >= 0;
  if (!written || !closed) throw Error(hdf5_reason() + " (writing '" + where + "/" + name + "')");
}

// The dataset's dimensions and values, converted to T by libhdf5.
template <class T>
std::vector<T> read_dataset(hid_t group, const char* name, std::vector<hsize_t>& dims,
                            const std::string& where) {
  silence_hdf5();
  const Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  if (!set.ok()) throw Error("no dataset '" + where + "/" + name + "'");
  const Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  dims.assign(static_cast<std::size_t>(std::max(rank, 0)), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  std::vector<T> values(static_cast<std::size_t>(count));
  if (count > 0 &&
      H5Dread(set.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw Error("cannot read dataset '" + where + "/" + name + "'");
  return values;
}

// Link creation that makes missing parent groups, as h5py's create_group does. Made once: a
// property list costs as much to make as a small dataset. Never closed (libhdf5 closes it at exit).
hid_t with_parents() {
  static const hid_t list = [] {
    const hid_t made = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(made, 1);
    return made;
  }();
  return list;
}

Handle create_group(hid_t file, const std::string& name, const std::string& path) {
  Handle group(H5Gcreate2(file, name.c_str(), with_parents(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!group.ok())
    throw Error(hdf5_reason() + " (creating group '" + name + "' in '" + path + "')");
  return group;
}

// Removes a group: one a killed run left without its last dataset, or one being replaced.
void remove_group(hid_t file, const std::string& name) {
  if (exists(file, name)) H5Ldelete(file, name.c_str(), H5P_DEFAULT);
}

}  // namespace

namespace {

// Why `path` cannot be opened or created as an HDF5 file, in the words a user acts on: a missing
// folder, a directory, a file another process holds locked, a file that is not HDF5 or is damaged.
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
    return "cannot open '" + path +
           "': another process holds it locked (another aief writing it? wait until it ends)";
  if (!creating && H5Fis_hdf5(path.c_str()) == 0)
    return "cannot open '" + path + "': it is not an HDF5 file";
  const int fd = ::open(path.c_str(), creating ? O_RDWR | O_CREAT | O_EXCL : O_RDONLY, 0644);
  if (fd < 0)
    return std::string("cannot ") + (creating ? "create '" : "open '") + path +
           "': " + std::strerror(errno);
  ::close(fd);
  if (creating) fs::remove(path, ec);
  return "cannot open '" + path + "' as an HDF5 file: it is damaged (libhdf5: " + hdf5_said + ")";
}

// The bytes the datasets of group `name` hold (what a copy of it writes besides metadata).
std::uint64_t group_storage_bytes(hid_t file, const std::string& name) {
  const Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) throw Error("'" + name + "' is not a group");
  const auto visit = [](hid_t parent, const char* link, const H5L_info_t*, void* data) -> herr_t {
    const Handle set(H5Dopen2(parent, link, H5P_DEFAULT), H5Dclose);
    if (set.ok()) *static_cast<std::uint64_t*>(data) += H5Dget_storage_size(set.get());
    return 0;
  };
  std::uint64_t bytes = 0;
  H5Literate(group.get(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, visit, &bytes);
  return bytes;
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

// Copies the file `from` to `to` (created), throwing the system's reason (std::filesystem's
// copy reports a full disk as "Input/output error").
void copy_file(const std::string& from, const std::string& to) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw Error("cannot read '" + from + "': " + std::strerror(errno));
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0) {
    const int code = errno;
    ::close(in);
    throw Error("cannot create '" + to + "': " + std::strerror(code));
  }
  std::vector<char> buffer(1 << 20);
  int code = 0;
  for (ssize_t n; code == 0 && (n = ::read(in, buffer.data(), buffer.size())) != 0;) {
    if (n < 0) {
      if (errno != EINTR) code = errno;
      continue;
    }
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(out, buffer.data() + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) {
        code = errno;
        break;
      }
      done += w;
    }
  }
  ::close(in);
  if (::close(out) != 0 && code == 0) code = errno;
  if (code != 0) throw Error(std::strerror(code) + std::string(" (copying '") + from + "')");
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path, Mode mode) : path_(path) {
  silence_hdf5();
  std::error_code ec;
  bool creating = false;
  if (mode != Mode::read_write) {
    if (!std::filesystem::exists(path, ec)) throw Error("cannot open '" + path + "': no such file");
    const std::size_t cache_bytes =
        mode == Mode::read_in_name_order ? kInNameOrderCacheBytes : kReadCacheBytes;
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, read_access(cache_bytes).get());
  } else if (std::filesystem::exists(path, ec)) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  } else {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_EXCL, file_creation().get(), H5P_DEFAULT);
    creating = true;
  }
  if (file_ < 0) throw Error(open_failure(path, creating, hdf5_reason()));
  if (mode == Mode::read_write) {
    void* handle = nullptr;
    const Handle access(H5Fget_access_plist(file_), H5Pclose);
    if (H5Pget_driver(access.get()) == H5FD_SEC2 &&
        H5Fget_vfd_handle(file_, H5P_DEFAULT, &handle) >= 0 && handle)
      descriptor_ = *static_cast<int*>(handle);
    reserved_until_ = static_cast<std::uint64_t>(std::filesystem::file_size(path, ec));
    const auto visit = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
      if (info->type == H5O_TYPE_GROUP)
        static_cast<std::unordered_set<std::uint64_t>*>(data)->insert(
            std::hash<std::string_view>{}(name));
      return 0;
    };
    if (H5Ovisit2(file_, H5_INDEX_NAME, H5_ITER_NATIVE, visit, &groups_, H5O_INFO_BASIC) < 0)
      throw Error("cannot list the groups of '" + path_ + "'");
    groups_known_ = true;
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

void Hdf5File::copy_group_from(const Hdf5File& source, const std::string& name) {
  silence_hdf5();
  const std::uint64_t bytes = group_storage_bytes(source.file_, name);
  write_guarded(
      bytes, "'" + name + "' from '" + source.path_ + "'",
      [&] {
        if (may_hold(name)) remove_group(file_, name);  // an incomplete group of the same name
        if (H5Ocopy(source.file_, name.c_str(), file_, name.c_str(), H5P_DEFAULT, with_parents()) <
            0)
          throw Error(hdf5_reason());
        note_group(name);
      },
      Flush::at_close);
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
}

template <class Write>
void Hdf5File::write_guarded(std::uint64_t bytes, const std::string& what, Write&& write,
                             Flush flush) {
  silence_hdf5();
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
                " (what was complete before is kept)");
  }
  try {
    write();
    if (flush == Flush::now || (flush == Flush::batched && ++unflushed_writes_ >= kWritesPerFlush))
      flush_now();
  } catch (const std::exception& e) {
    failure_ = e.what();
    fence();
    throw Error("cannot write " + what + " to '" + path_ + "': " + failure_ +
                " (what was complete before is kept)");
  }
}

bool Hdf5File::has_features(const std::string& name) const {
  return may_hold(name) && exists(file_, name + "/image_size");
}

namespace {

// A string attribute of an object, or "" when it has none.
std::string string_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return "";
  const Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  const Handle stored(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(stored.get()) != H5T_STRING) return "";
  if (H5Tis_variable_str(stored.get()) <= 0) {  // fixed length
    std::string value(H5Tget_size(stored.get()), '\0');
    if (H5Aread(attribute.get(), stored.get(), value.data()) < 0) return "";
    return value.substr(0, value.find('\0'));
  }
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  char* text = nullptr;
  if (H5Aread(attribute.get(), type.get(), &text) < 0 || !text) return "";
  std::string value(text);
  H5free_memory(text);
  return value;
}

// A UTF-8 string attribute: variable length (what h5py writes for a str, and reads back as one),
// or fixed length, the value's bytes without a terminator (about a third cheaper to write; h5py
// reads it as bytes), for the pair names only aief reads.
enum class StringLength { variable, fixed };
void write_string_attribute(hid_t object, const char* name, const std::string& value,
                            StringLength length = StringLength::variable) {
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  const bool fixed = length == StringLength::fixed;
  H5Tset_size(type.get(), fixed ? std::max<std::size_t>(value.size(), 1) : H5T_VARIABLE);
  if (fixed) H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const Handle attribute(
      H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const char* text = value.c_str();
  const void* buffer = fixed ? static_cast<const void*>(text) : static_cast<const void*>(&text);
  if (!attribute.ok() || H5Awrite(attribute.get(), type.get(), buffer) < 0)
    throw Error(hdf5_reason() + " (attribute '" + name + "')");
}

}  // namespace

namespace {

// Throws when the pair group `group` (named `group_name`) records names other than the pair's.
void check_recorded_names(hid_t group, const std::string& group_name, const std::string& name0,
                          const std::string& name1, const std::string& path) {
  const std::string stored0 = string_attribute(group, "name0"),
                    stored1 = string_attribute(group, "name1");
  if (stored0.empty() && stored1.empty()) return;  // written before names were recorded
  if (stored0 != name0 || stored1 != name1)
    throw Error("pair '" + name0 + " " + name1 + "' and pair '" + stored0 + " " + stored1 +
                "' share the group '" + group_name + "' in '" + path +
                "' (hloc's names: '/' becomes '-'), which holds the second's matches");
}

// The matches a pair group holds (query = index in image 0); distance from matching_scores0.
std::vector<Match> read_pair_group(hid_t group, const std::string& group_name,
                                   const std::string& path) {
  std::vector<hsize_t> dims;
  const std::vector<std::int32_t> matches0 =
      read_dataset<std::int32_t>(group, "matches0", dims, group_name);
  std::vector<float> scores0(matches0.size(), 1.0f);
  if (H5Lexists(group, "matching_scores0", H5P_DEFAULT) > 0)
    scores0 = read_dataset<float>(group, "matching_scores0", dims, group_name);
  if (scores0.size() != matches0.size())
    throw Error("'" + group_name + "' in '" + path +
                "': matches0 and matching_scores0 differ in length");
  std::vector<Match> matches;
  for (std::size_t i = 0; i < matches0.size(); ++i)
    if (matches0[i] >= 0)
      matches.push_back({static_cast<int>(i), matches0[i],
                         static_cast<int>(std::lround((1.0f - scores0[i]) * 256.0f))});
  return matches;
}

// The group `name` opened, or an invalid handle when the file has none: one walk of the path
// (exists() walks it once per component; a missing group is the rare case).
Handle open_group_if_any(hid_t file, const std::string& name) {
  silence_hdf5();
  return Handle(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
}

}  // namespace

void Hdf5File::check_pair_owner(const std::string& group_name, const std::string& name0,
                                const std::string& name1) const {
  const Handle group = open_group_if_any(file_, group_name);
  if (group.ok()) check_recorded_names(group.get(), group_name, name0, name1, path_);
}

bool Hdf5File::has_matches(const std::string& name0, const std::string& name1) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  if (!may_hold(group_name)) return false;
  const Handle group = open_group_if_any(file_, group_name);
  if (!group.ok() || H5Lexists(group.get(), "matching_scores0", H5P_DEFAULT) <= 0) return false;
  check_recorded_names(group.get(), group_name, name0, name1, path_);
  return true;
}

std::vector<Match> Hdf5File::read_matches(const std::string& name0,
                                          const std::string& name1) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  const Handle group = open_group_if_any(file_, group_name);
  if (!group.ok()) throw Error("no pair '" + name0 + " " + name1 + "' in '" + path_ + "'");
  check_recorded_names(group.get(), group_name, name0, name1, path_);
  return read_pair_group(group.get(), group_name, path_);
}

std::optional<std::vector<Match>> Hdf5File::find_matches(const std::string& name0,
                                                         const std::string& name1) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  if (!may_hold(group_name)) return std::nullopt;
  const Handle group = open_group_if_any(file_, group_name);
  if (!group.ok() || H5Lexists(group.get(), "matching_scores0", H5P_DEFAULT) <= 0)
    return std::nullopt;
  check_recorded_names(group.get(), group_name, name0, name1, path_);
  return read_pair_group(group.get(), group_name, path_);
}

bool Hdf5File::features_belong_to(const std::string& name, const SourceRecord& source) const {
  if (!has_features(name) || !exists(file_, name + "/source")) return false;
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  std::vector<hsize_t> dims;
  const std::vector<std::int64_t> stored =
      read_dataset<std::int64_t>(group.get(), "source", dims, name);
  return stored.size() == 2 && static_cast<std::uintmax_t>(stored[0]) == source.bytes &&
         stored[1] == source.mtime_ns;
}

std::optional<std::string> Hdf5File::option_record(const std::string& name) const {
  silence_hdf5();
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) return std::nullopt;
  std::string record = string_attribute(group.get(), "options");
  if (record.empty()) return std::nullopt;
  return record;
}

void Hdf5File::remove_features(const std::string& name) {
  // Flushed at once: a file created by an older aief hands freed space out again.
  write_guarded(
      0, "the removal of '" + name + "'", [&] { remove_group(file_, name); }, Flush::now);
}

void Hdf5File::write_features(const std::string& name, const Features& features,
                              const SourceRecord* source, const ExtractorOptions* options) {
  silence_hdf5();
  // A group being replaced goes first, flushed, so that no new data lands in its space while the
  // file on disk still holds it.
  if (may_hold(name) && exists(file_, name)) remove_features(name);
  const std::size_t n = features.keypoints.size();
  std::vector<float> xy(2 * n), size(n), angle(n), response(n);
  std::vector<std::int32_t> octave(n);
  std::vector<std::uint8_t> descriptors(kDescriptorBytes * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Keypoint& kp = features.keypoints[i];
    xy[2 * i] = kp.x;
    xy[2 * i + 1] = kp.y;
    size[i] = kp.size;
    angle[i] = kp.angle_deg;
    response[i] = kp.response;
    octave[i] = kp.octave;
    for (std::size_t b = 0; b < kDescriptorBytes; ++b)
      descriptors[b * n + i] = features.descriptors[i][b];  // 32 x N
  }
  const hsize_t count = n;
  const std::uint64_t bytes =
      n * (2 * sizeof(float) + kDescriptorBytes + 3 * sizeof(float) + sizeof(std::int32_t));
  write_guarded(bytes, "image '" + name + "'", [&] {
    const Handle group = create_group(file_, name, path_);
    note_group(name);
    write_dataset(group.get(), "keypoints", {count, 2}, xy, name);
    write_dataset(group.get(), "descriptors", {kDescriptorBytes, count}, descriptors, name);
    write_dataset(group.get(), "scores", {count}, response, name);
    write_dataset(group.get(), "size", {count}, size, name);
    write_dataset(group.get(), "angle", {count}, angle, name);
    write_dataset(group.get(), "octave", {count}, octave, name);
    if (source)
      write_dataset(
          group.get(), "source", {2},
          std::vector<std::int64_t>{static_cast<std::int64_t>(source->bytes), source->mtime_ns},
          name);
    if (options) write_string_attribute(group.get(), "options", option_record_json(*options));
    // Last: its presence marks the group complete (has_features).
    write_dataset(group.get(), "image_size", {2},
                  std::vector<std::int64_t>{features.image_width, features.image_height}, name);
  });
}

std::vector<Descriptor> Hdf5File::read_descriptors(const std::string& name) const {
  if (!exists(file_, name + "/descriptors"))
    throw Error("no image '" + name + "' in '" + path_ + "'");
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  std::vector<hsize_t> dims;
  const std::vector<std::uint8_t> bytes =
      read_dataset<std::uint8_t>(group.get(), "descriptors", dims, name);
  if (dims.size() != 2 || dims[0] != kDescriptorBytes)
    throw Error("'" + name + "/descriptors' in '" + path_ +
                "' is not 32 x N (aief's binary descriptors)");
  const std::size_t n = dims[1];
  std::vector<Descriptor> descriptors(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < kDescriptorBytes; ++b) descriptors[i][b] = bytes[b * n + i];
  return descriptors;
}

Features Hdf5File::read_features(const std::string& name) const {
  if (!exists(file_, name)) throw Error("no image '" + name + "' in '" + path_ + "'");
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) throw Error("'" + name + "' in '" + path_ + "' is not a group");
  std::vector<hsize_t> dims;
  const std::vector<float> xy = read_dataset<float>(group.get(), "keypoints", dims, name);
  if (dims.size() != 2 || dims[1] != 2)
    throw Error("'" + name + "/keypoints' in '" + path_ + "' is not N x 2");
  const std::size_t n = dims[0];
  const std::vector<std::uint8_t> descriptors =
      read_dataset<std::uint8_t>(group.get(), "descriptors", dims, name);
  if (dims.size() != 2 || dims[0] != kDescriptorBytes || dims[1] != n)
    throw Error("'" + name + "/descriptors' in '" + path_ + "' is not 32 x " + std::to_string(n) +
                " (aief's binary descriptors)");
  // Each read in the type it is stored as: a conversion would cost libhdf5 a 1 MB buffer cleared
  // per read (about 1 M instructions, more than the rest of the image).
  const auto optional = [&](const char* dataset, auto zero) {
    std::vector<hsize_t> d;
    using T = decltype(zero);
    return exists(group.get(), dataset) ? read_dataset<T>(group.get(), dataset, d, name)
                                        : std::vector<T>(n, zero);
  };
  const std::vector<float> scores = optional("scores", 0.0f), size = optional("size", 0.0f),
                           angle = optional("angle", 0.0f);
  const std::vector<std::int32_t> octave = optional("octave", std::int32_t{0});
  const std::vector<std::int64_t> image_size =
      read_dataset<std::int64_t>(group.get(), "image_size", dims, name);
  Features features;
  if (image_size.size() == 2) {
    features.image_width = static_cast<int>(image_size[0]);
    features.image_height = static_cast<int>(image_size[1]);
  }
  features.keypoints.resize(n);
  features.descriptors.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Keypoint& kp = features.keypoints[i];
    kp.x = xy[2 * i];
    kp.y = xy[2 * i + 1];
    kp.size = i < size.size() ? size[i] : 0;
    kp.angle_deg = i < angle.size() ? angle[i] : 0;
    kp.response = i < scores.size() ? scores[i] : 0;
    kp.octave = i < octave.size() ? static_cast<int>(octave[i]) : 0;
    for (std::size_t b = 0; b < kDescriptorBytes; ++b)
      features.descriptors[i][b] = descriptors[b * n + i];
  }
  return features;
}

void Hdf5File::write_matches(const std::string& name0, const std::string& name1, int keypoints0,
                             const std::vector<Match>& matches) {
  silence_hdf5();
  const std::string pair_name = hloc_pair_name(name0, name1);
  if (may_hold(pair_name) && exists(file_, pair_name)) {
    check_pair_owner(pair_name, name0, name1);
    write_guarded(
        0, "the removal of '" + pair_name + "'", [&] { remove_group(file_, pair_name); },
        Flush::now);
  }
  std::vector<std::int32_t> matches0(static_cast<std::size_t>(keypoints0), -1);
  std::vector<float> scores0(static_cast<std::size_t>(keypoints0), 0.0f);
  for (const Match& m : matches) {
    matches0[static_cast<std::size_t>(m.query)] = m.train;
    scores0[static_cast<std::size_t>(m.query)] = 1.0f - static_cast<float>(m.distance) / 256.0f;
  }
  const hsize_t n = matches0.size();
  write_guarded(n * (sizeof(std::int32_t) + sizeof(float)), "pair '" + pair_name + "'", [&] {
    const Handle group = create_group(file_, pair_name, path_);
    note_group(pair_name);
    write_string_attribute(group.get(), "name0", name0, StringLength::fixed);
    write_string_attribute(group.get(), "name1", name1, StringLength::fixed);
    write_dataset(group.get(), "matches0", {n}, matches0, pair_name);
    write_dataset(group.get(), "matching_scores0", {n}, scores0,
                  pair_name);  // last: marks the pair complete
  });
}

std::vector<std::string> Hdf5File::feature_names() const {
  silence_hdf5();
  std::vector<std::string> names;
  const auto visit = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
    const std::string path(name);
    const std::string suffix = "/image_size";
    if (info->type == H5O_TYPE_DATASET && path.size() > suffix.size() && path.ends_with(suffix))
      static_cast<std::vector<std::string>*>(data)->push_back(
          path.substr(0, path.size() - suffix.size()));
    return 0;
  };
  // Only each object's type (H5O_INFO_BASIC): the full information reads every header's
  // attributes and sizes too, 340k instructions an image.
  if (H5Ovisit2(file_, H5_INDEX_NAME, H5_ITER_INC, visit, &names, H5O_INFO_BASIC) < 0)
    throw Error("cannot list the groups of '" + path_ + "'");
  std::sort(names.begin(), names.end());
  return names;
}

int merge_feature_files(const std::string& output, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // Every input checked first: each opens, no image is in two of them (a hash set: linear), and
  // every image, those already in the output included, was extracted with the same options.
  SameOptionsCheck same_options;
  std::unordered_set<std::string> kept;  // images already in the output, from an earlier merge
  const bool extending = fs::exists(output, ec);
  if (extending) {
    const Hdf5File previous(output, Hdf5File::Mode::read_in_name_order);
    for (std::string& name : previous.feature_names()) {
      same_options.check(previous, name);
      kept.insert(std::move(name));
    }
  }
  std::vector<std::unique_ptr<Hdf5File>> shards;
  std::vector<std::vector<std::string>> names;  // each shard's, kept for the copy
  names.reserve(inputs.size());
  // Each image's shard, keyed by the names above (not copies of them: 48 bytes less an image).
  std::unordered_map<std::string_view, std::size_t> first_shard;
  for (const std::string& input : inputs) {
    shards.push_back(std::make_unique<Hdf5File>(input, Hdf5File::Mode::read_in_name_order));
    names.push_back(shards.back()->feature_names());
    for (const std::string& name : names.back()) {
      const auto [at, inserted] = first_shard.emplace(name, shards.size() - 1);
      if (!inserted)
        throw Error("image '" + name + "' is in two of the files merged, '" + inputs[at->second] +
                    "' and '" + input + "'; nothing was written");
      if (!kept.count(name)) same_options.check(*shards.back(), name);
    }
  }
  if (const fs::path folder = fs::path(output).parent_path();
      !extending && !folder.empty() && !fs::is_directory(folder, ec))
    throw Error("cannot create '" + output + "': the folder '" + folder.string() +
                "' does not exist");

  // Then written to a temporary beside the output (a copy of it when extending), renamed over it
  // only when complete: a failed merge leaves the output as it was.
  const std::string temporary = temporary_path_of(output);
  fs::remove(temporary, ec);
  int copied = 0;
  try {
    if (extending) copy_file(output, temporary);
    Hdf5File out(temporary, Hdf5File::Mode::read_write);
    for (std::size_t s = 0; s < shards.size(); ++s)
      for (const std::string& name : names[s]) {
        if (kept.count(name)) continue;
        out.copy_group_from(*shards[s], name);
        ++copied;
      }
    out.close();
  } catch (const fs::filesystem_error& e) {
    fs::remove(temporary, ec);
    throw Error("cannot merge into '" + output + "' (left as it was): " + e.code().message());
  } catch (const std::exception& e) {
    fs::remove(temporary, ec);
    throw Error("cannot merge into '" + output + "' (left as it was): " + e.what());
  }
  fs::rename(temporary, output, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw Error("cannot merge into '" + output + "' (left as it was): " + ec.message());
  }
  return copied;
}

}  // namespace aief::io

#pragma once
// libhdf5's objects as io/hdf5_*.cpp use them (internal to io/, never included elsewhere): a
// handle closed by its own close function, libhdf5's errors turned into aief::Error reasons,
// datasets, string attributes and groups. Files (open, close, space) are io/hdf5_file.hpp.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <hdf5.h>

#include "aief/error.hpp"

namespace aief::io::hdf5 {

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
void silence_hdf5();

// The reason libhdf5 gives for the last failure on this thread: the system's message when a
// read or write of the file failed ("No space left on device"), else its innermost description.
std::string hdf5_reason();

// "cannot open 'f.h5' as an HDF5 file: it is damaged or cut short (libhdf5: why), if it is the
// output of a run that was killed ... move it away and run that command again": a file libhdf5
// cannot read, named with what to do, never a dead end. `hdf5_said` may be empty.
std::string damaged_file(const std::string& path, const std::string& hdf5_said);

// Whether every component of `path` exists (H5Lexists fails when a parent is missing).
bool exists(hid_t file, const std::string& path);

template <class T>
hid_t native_type();
template <>
inline hid_t native_type<float>() {
  return H5T_NATIVE_FLOAT;
}
template <>
inline hid_t native_type<std::uint8_t>() {
  return H5T_NATIVE_UINT8;
}
template <>
inline hid_t native_type<std::int32_t>() {
  return H5T_NATIVE_INT32;
}
template <>
inline hid_t native_type<std::int64_t>() {
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
hid_t with_parents();

Handle create_group(hid_t file, const std::string& name, const std::string& path);

// Removes a group: one a killed run left without its last dataset, or one being replaced.
void remove_group(hid_t file, const std::string& name);

// The group `name` opened, or an invalid handle when the file has none: one walk of the path
// (exists() walks it once per component; a missing group is the rare case).
Handle open_group_if_any(hid_t file, const std::string& name);

// A string attribute of an object, or "" when it has none.
std::string string_attribute(hid_t object, const char* name);

// A UTF-8 string attribute: variable length (what h5py writes for a str, and reads back as one),
// or fixed length, the value's bytes without a terminator (about a third cheaper to write; h5py
// reads it as bytes), for the pair names only aief reads.
enum class StringLength { variable, fixed };
void write_string_attribute(hid_t object, const char* name, const std::string& value,
                            StringLength length = StringLength::variable);

}  // namespace aief::io::hdf5

#pragma once
// Why a whole HDF5 file cannot be opened for writing. libhdf5 names no reason a user acts on
// when it cannot open an existing file read-write (a read-only file system, a file without write
// permission, a file another handle in this process holds), and such a file was called "damaged
// or cut short ... move it away", though nothing was wrong with it.
#include <string>

namespace aief::io {

// When `path` opens read-only as HDF5 (so it is whole): "cannot open 'x' for writing: <why>; the
// file itself is whole (it opens for reading) and was left as it was". "" when it does not open
// read-only either (then it is damaged, and the caller says so).
std::string whole_file_not_writable(const std::string& path, const std::string& hdf5_said);

}  // namespace aief::io

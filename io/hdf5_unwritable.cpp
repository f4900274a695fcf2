#include "io/hdf5_unwritable.hpp"

#include <cerrno>
#include <cstring>

#include <hdf5.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "io/hdf5_objects.hpp"

namespace aief::io {

std::string whole_file_not_writable(const std::string& path, const std::string& hdf5_said) {
  hdf5::silence_hdf5();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return "";
  H5Fclose(file);
  std::string why;
  struct statvfs volume {};
  struct stat status {};
  if (::statvfs(path.c_str(), &volume) == 0 && (volume.f_flag & ST_RDONLY) != 0) {
    why =
        "it is on a read-only file system (write the output elsewhere, or copy the file to a "
        "writable folder first)";
  } else if (::access(path.c_str(), W_OK) != 0) {
    const int error = errno;
    why = error == EACCES || error == EPERM
              ? "you have no permission to write it" +
                    (::stat(path.c_str(), &status) == 0
                         ? " (owner uid " + std::to_string(status.st_uid) + ", mode " +
                               std::to_string((status.st_mode >> 6) & 7) +
                               std::to_string((status.st_mode >> 3) & 7) +
                               std::to_string(status.st_mode & 7) + ")"
                         : std::string())
              : std::string(error == EROFS ? "it is on a read-only file system"
                                           : std::strerror(error));
  } else {
    why =
        "another handle holds it open (an h5py.File or another aief.FeaturesFile on it in this "
        "process? close that one first)" +
        (hdf5_said.empty() ? std::string() : " (libhdf5: " + hdf5_said + ")");
  }
  return "cannot open '" + path + "' for writing: " + why +
         "; the file itself is whole (it opens for reading) and was left as it was";
}

}  // namespace aief::io

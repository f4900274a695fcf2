#include "io/source_record.hpp"

#include <cerrno>
#include <cstring>

#include <sys/stat.h>

#include "aief/error.hpp"

namespace aief::io {

SourceRecord source_record_of(const std::string& path, const std::string& name) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw Error("cannot open image '" + path + "': " + std::strerror(errno));
  SourceRecord record;
  record.name = name;
  record.bytes = static_cast<std::uintmax_t>(info.st_size);
  record.mtime_ns =
      static_cast<long long>(info.st_mtim.tv_sec) * 1'000'000'000LL + info.st_mtim.tv_nsec;
  return record;
}

}  // namespace aief::io

// A file system without fallocate (NFSv3, FUSE, older ZFS), for a test: LD_PRELOAD this library
// and every fallocate / posix_fallocate fails with EOPNOTSUPP, as such a file system answers.
// Built as tests' helper only (tests/CMakeLists.txt); tests/test_disk_full.cpp runs the CLI with
// it.
#include <sys/types.h>
#include <cerrno>

extern "C" {

int fallocate(int, int, off_t, off_t) {
  errno = EOPNOTSUPP;
  return -1;
}
int fallocate64(int, int, off64_t, off64_t) {
  errno = EOPNOTSUPP;
  return -1;
}
int posix_fallocate(int, off_t, off_t) { return EOPNOTSUPP; }
int posix_fallocate64(int, off64_t, off64_t) { return EOPNOTSUPP; }

}  // extern "C"

// A file system without locks (Lustre mounted without -o flock, NFS without its lock daemon), for
// a test: LD_PRELOAD this library and every fcntl lock request (open file description and POSIX
// record locks) and every flock fails with ENOSYS, as Lustre answers, or with ENOLCK, as NFS
// without its lock daemon answers, when AIEF_NO_LOCKS_ERRNO=ENOLCK; every other fcntl command
// goes to the C library. Built as tests' helper only (tests/CMakeLists.txt);
// tests/test_output_lock.cpp runs the CLI with it.
#include <dlfcn.h>
#include <fcntl.h>
#include <cerrno>
#include <cstdarg>
#include <cstdlib>
#include <cstring>

namespace {

bool is_lock_request(int command) {
  return command == F_SETLK || command == F_SETLKW || command == F_GETLK ||
         command == F_OFD_SETLK || command == F_OFD_SETLKW || command == F_OFD_GETLK;
}

int lock_errno() {
  const char* answer = std::getenv("AIEF_NO_LOCKS_ERRNO");
  return answer && std::strcmp(answer, "ENOLCK") == 0 ? ENOLCK : ENOSYS;
}

using Fcntl = int (*)(int, int, ...);

int forward(const char* symbol, int fd, int command, void* argument) {
  static Fcntl next_fcntl = reinterpret_cast<Fcntl>(dlsym(RTLD_NEXT, "fcntl"));
  static Fcntl next_fcntl64 = reinterpret_cast<Fcntl>(dlsym(RTLD_NEXT, "fcntl64"));
  const Fcntl next = symbol[5] == '6' && next_fcntl64 ? next_fcntl64 : next_fcntl;
  return next(fd, command, argument);
}

}  // namespace

extern "C" {

int fcntl(int fd, int command, ...) {
  va_list arguments;
  va_start(arguments, command);
  void* argument = va_arg(arguments, void*);
  va_end(arguments);
  if (is_lock_request(command)) {
    errno = lock_errno();
    return -1;
  }
  return forward("fcntl", fd, command, argument);
}

int fcntl64(int fd, int command, ...) {
  va_list arguments;
  va_start(arguments, command);
  void* argument = va_arg(arguments, void*);
  va_end(arguments);
  if (is_lock_request(command)) {
    errno = lock_errno();
    return -1;
  }
  return forward("fcntl64", fd, command, argument);
}

int flock(int, int) {
  errno = lock_errno();
  return -1;
}

}  // extern "C"

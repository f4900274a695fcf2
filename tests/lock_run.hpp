#pragma once
// Shared by the tests of aief's own lock (tests/test_output_lock.cpp, test_lock_file.cpp): the
// built tool (AIEF_CLI_PATH) started with libhdf5's lock off, as on a cluster file system, or on,
// optionally as another user (a member of a group folder), and a folder of sample images.
#include <fcntl.h>
#include <grp.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

extern char** environ;

namespace aief::test::lock {

namespace fs = std::filesystem;

inline std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// How a run is started: its environment's additions ("NAME=value"), whether libhdf5's own lock
// stays on (off by default: HDF5_USE_FILE_LOCKING=FALSE), and as whom (uid -1: this user).
struct How {
  std::vector<std::string> extra;
  bool libhdf5_lock = false;
  uid_t uid = static_cast<uid_t>(-1);
  gid_t gid = 0;
  mode_t umask = 022;
  fs::path cli = AIEF_CLI_PATH;  // a run as another user takes cli_for_others' copy
};

// A copy of the CLI in `folder` that another user can run: the build folder may be out of their
// reach (CI's fresh root builds below /root, mode 0700: exec fails and the run ends with 127).
inline fs::path cli_for_others(const fs::path& folder) {
  const fs::path copy = folder / "aief_cli";
  if (!fs::exists(copy)) fs::copy_file(AIEF_CLI_PATH, copy);
  fs::permissions(copy, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                            fs::perms::others_read | fs::perms::others_exec);
  return copy;
}

// Starts the CLI with `arguments`, stdout to `log` and stderr to `log`.err.
inline pid_t start(const std::vector<std::string>& arguments, const fs::path& log, How how = {}) {
  std::vector<std::string> copies = {how.cli.string()};
  copies.insert(copies.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  if (!how.libhdf5_lock) how.extra.push_back("HDF5_USE_FILE_LOCKING=FALSE");
  std::vector<char*> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("HDF5_USE_FILE_LOCKING=", 0) != 0) env.push_back(*e);
  for (std::string& e : how.extra) env.push_back(e.data());
  env.push_back(nullptr);
  const std::string out = log.string(), errors = log.string() + ".err";
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  // The child: only async-signal-safe calls from here.
  if (how.uid != static_cast<uid_t>(-1) &&
      (::setgroups(1, &how.gid) != 0 || ::setgid(how.gid) != 0 || ::setuid(how.uid) != 0))
    ::_exit(126);
  ::umask(how.umask);
  const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
  const int e = ::open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (o < 0 || e < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0) ::_exit(126);
  ::execve(argv[0], argv.data(), env.data());
  ::_exit(127);
}

inline int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline int run(const std::vector<std::string>& arguments, const fs::path& log, How how = {}) {
  return wait_for(start(arguments, log, std::move(how)));
}

// A folder of `count` images named prefix0.png ... (the bundled images under several names).
inline fs::path image_folder(const fs::path& root, const std::string& prefix, int count) {
  const fs::path folder = root / prefix;
  fs::create_directories(folder);
  const char* const sequences[] = {"graf", "boat", "leuven"};
  for (int i = 0; i < count; ++i)
    fs::copy_file(aief::test::sample_path(sequences[i % 3], i % 2 ? "img2.png" : "img1.png"),
                  folder / (prefix + std::to_string(i) + ".png"));
  return folder;
}

// The batch command that writes `h5` from `images`.
inline std::vector<std::string> batch_into(const fs::path& images, const fs::path& h5) {
  return {"extract", "--batch", images.string(), "-o", h5.string(), "--format", "h5"};
}

}  // namespace aief::test::lock

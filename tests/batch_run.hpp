#pragma once
// Shared by the tests of aief extract --batch (tests/test_batch_resume.cpp, test_batch_names.cpp):
// the built tool (AIEF_CLI_PATH, which tests/CMakeLists.txt gives the CLI tests) started and
// waited for, and the outputs found and checked.
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <opencv2/core.hpp>

#include "io/feature_formats.hpp"
#include "io/source_record.hpp"

extern char** environ;

namespace aief::test::batch {

namespace fs = std::filesystem;

// The files below `folder` with `extension`, as paths relative to it.
inline std::set<std::string> files_below(const fs::path& folder, const std::string& extension) {
  std::set<std::string> names;
  if (fs::exists(folder))
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.is_regular_file() && entry.path().string().size() > extension.size() &&
          entry.path().string().compare(entry.path().string().size() - extension.size(),
                                        extension.size(), extension) == 0)
        names.insert(entry.path().lexically_relative(folder).generic_string());
  return names;
}

inline pid_t start(const std::vector<std::string>& arguments, const fs::path& log = "/dev/null") {
  std::vector<char*> argv;
  std::string binary = AIEF_CLI_PATH;
  argv.push_back(binary.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  // stderr beside the log (a sanitizer's report, a message), or nowhere when there is no log.
  const std::string errors = log == "/dev/null" ? log.string() : log.string() + ".err";
  posix_spawn_file_actions_addopen(&actions, 2, errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

inline int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Runs a batch to the end; returns the exit status, and its stdout in `report`.
inline int run_batch(const std::vector<std::string>& arguments, const fs::path& scratch,
                     std::string* report = nullptr) {
  const fs::path log = scratch / "batch.log";
  const int status = wait_for(start(arguments, log));
  if (report) *report = text_of(log);
  fs::remove(log);
  return status;
}

// The output parses (OpenCV's JSON reader), holds one descriptor per keypoint and records the
// input `name` read from `path`, with its current size and time.
inline void expect_output_of(const fs::path& output, const std::string& name,
                             const fs::path& path) {
  SCOPED_TRACE(output.string());
  cv::FileStorage file(output.string(), cv::FileStorage::READ);
  ASSERT_TRUE(file.isOpened());
  EXPECT_EQ(static_cast<std::string>(file["source"]["name"]), name);
  EXPECT_EQ(static_cast<double>(file["source"]["bytes"]), static_cast<double>(fs::file_size(path)));
  EXPECT_GT(file["keypoints"].size(), 10u);
  EXPECT_EQ(file["keypoints"].size(), file["descriptors_hex"].size());
  EXPECT_TRUE(aief::io::features_file_belongs_to(output.string(),
                                                 aief::io::source_record_of(path.string(), name)));
}

}  // namespace aief::test::batch

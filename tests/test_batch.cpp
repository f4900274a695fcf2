// aief extract --batch: resumes after being killed halfway (no half-written output, nothing
// redone), skips a corrupt image with its reason, shards split a collection exactly.
#include <csignal>
#include <fcntl.h>
#include <map>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include "tests/test_support.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;

struct BatchFolder {
  fs::path root = fs::temp_directory_path() / ("aief_batch_" + std::to_string(::getpid()));
  fs::path images = root / "images", out = root / "out";
  int count = 0;
  BatchFolder() {
    fs::remove_all(root);
    fs::create_directories(images / "nested");
    // The bundled images under several names: enough work to kill the run halfway.
    for (int copy = 0; copy < 4; ++copy)
      for (const char* sequence : {"graf", "boat", "leuven"})
        for (const char* file : {"img1.png", "img2.png"}) {
          const fs::path target = (copy % 2 ? images / "nested" : images) /
                                  (std::string(sequence) + "_" + std::to_string(copy) + "_" + file);
          fs::copy_file(aief::test::sample_path(sequence, file), target);
          ++count;
        }
    std::ofstream(images / "broken.png") << "\x89PNG\r\n\x1a\n but then nothing";
  }
  ~BatchFolder() { fs::remove_all(root); }

  std::set<std::string> outputs() const {
    std::set<std::string> names;
    if (fs::exists(out))
      for (const auto& entry : fs::directory_iterator(out))
        if (entry.path().extension() == ".json") names.insert(entry.path().filename().string());
    return names;
  }
};

pid_t start(const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  std::string binary = AIEF_CLI_PATH;
  argv.push_back(binary.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool complete_json(const fs::path& path) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.size() > 1000 && text.rfind("]\n}\n") == text.size() - 4 && text.find("\"descriptors_hex\"") != std::string::npos;
}

TEST(Batch, ResumesAfterBeingKilledHalfway) {
  BatchFolder folder;
  const std::vector<std::string> args = {"extract", "--batch", folder.images.string(), "-o", folder.out.string(), "--threads", "1"};
  const pid_t pid = start(args);
  ASSERT_GT(pid, 0);
  for (int i = 0; i < 2000 && folder.outputs().size() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  wait_for(pid);
  const std::set<std::string> before = folder.outputs();
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), static_cast<std::size_t>(folder.count)) << "the run finished before it could be killed";
  for (const std::string& name : before) EXPECT_TRUE(complete_json(folder.out / name)) << name << " is a half file";
  std::map<std::string, fs::file_time_type> stamps;
  for (const std::string& name : before) stamps[name] = fs::last_write_time(folder.out / name);

  // The second run finishes the job, leaves the first run's outputs alone, reports the broken image.
  EXPECT_EQ(wait_for(start(args)), 1) << "a failed image makes the exit status 1";
  const std::set<std::string> after = folder.outputs();
  EXPECT_EQ(after.size(), static_cast<std::size_t>(folder.count));
  for (const std::string& name : after) EXPECT_TRUE(complete_json(folder.out / name)) << name;
  for (const auto& [name, stamp] : stamps) EXPECT_EQ(fs::last_write_time(folder.out / name), stamp) << name << " was redone";
  EXPECT_TRUE(after.count("nested__graf_1_img1.json"));
  EXPECT_FALSE(after.count("broken.json"));
}

TEST(Batch, ShardsSplitTheCollectionExactly) {
  BatchFolder folder;
  std::set<std::string> seen;
  std::size_t total = 0;
  for (int shard = 0; shard < 3; ++shard) {
    const fs::path out = folder.root / ("shard" + std::to_string(shard));
    wait_for(start({"extract", "--batch", folder.images.string(), "-o", out.string(), "--shard", std::to_string(shard) + "/3",
                    "--features", "100"}));
    for (const auto& entry : fs::directory_iterator(out)) {
      seen.insert(entry.path().filename().string());
      ++total;
    }
  }
  EXPECT_EQ(total, static_cast<std::size_t>(folder.count)) << "an image in two shards, or in none";
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(folder.count));
}

}  // namespace

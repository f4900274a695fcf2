// aief's own lock on the HDF5 outputs (io/output_lock.hpp): two CLI runs writing one file at once,
// with libhdf5's lock turned off (HDF5_USE_FILE_LOCKING=FALSE, as on Lustre and GPFS), leave a
// whole file; two merges into one output lose no image; a writer waits while the lock is held and
// says who holds it; where no lock can be had (a file system without fcntl locks:
// tests/no_locks_shim.cpp) the write is refused, naming the file and the setting.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/output_lock.hpp"
#include "io/temporary_files.hpp"
#endif
#include "tests/test_support.hpp"

#ifdef AIEF_HAVE_HDF5

extern char** environ;

namespace {

namespace fs = std::filesystem;
using aief::test::TempFolder;

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Starts the CLI with `arguments`, stdout to `log` and stderr to `log`.err, its environment this
// process's with `extra` ("NAME=value") added: libhdf5's lock is always off here, as on a cluster
// file system.
pid_t start(const std::vector<std::string>& arguments, const fs::path& log,
            std::vector<std::string> extra = {}) {
  std::vector<std::string> copies = {AIEF_CLI_PATH};
  copies.insert(copies.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  extra.push_back("HDF5_USE_FILE_LOCKING=FALSE");
  std::vector<char*> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("HDF5_USE_FILE_LOCKING=", 0) != 0) env.push_back(*e);
  for (std::string& e : extra) env.push_back(e.data());
  env.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const std::string errors = log.string() + ".err";
  posix_spawn_file_actions_addopen(&actions, 2, errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int run(const std::vector<std::string>& arguments, const fs::path& log,
        const std::vector<std::string>& extra = {}) {
  return wait_for(start(arguments, log, extra));
}

// A folder of `count` images named prefix0.png ... (the bundled images under several names).
fs::path image_folder(const fs::path& root, const std::string& prefix, int count) {
  const fs::path folder = root / prefix;
  fs::create_directories(folder);
  const char* const sequences[] = {"graf", "boat", "leuven"};
  for (int i = 0; i < count; ++i)
    fs::copy_file(aief::test::sample_path(sequences[i % 3], i % 2 ? "img2.png" : "img1.png"),
                  folder / (prefix + std::to_string(i) + ".png"));
  return folder;
}

std::set<std::string> names_in(const fs::path& h5) {
  const aief::io::Hdf5File file(h5.string(), aief::io::Hdf5File::Mode::read);
  const std::vector<std::string> names = file.feature_names();
  return {names.begin(), names.end()};
}

TEST(OutputLock, TwoBatchesIntoOneH5AtOnceWithoutLibhdf5sLockLeaveAWholeFile) {
  // A resubmitted Slurm task while the first still runs: before, both said they extracted and the
  // file never opened again ("unknown message with 'fail if unknown' flag found").
  const TempFolder temp("aief_output_lock");
  const fs::path images = image_folder(temp.path(), "f", 24), h5 = temp.path() / "two.h5";
  const std::vector<std::string> args = {"extract",  "--batch", images.string(), "-o", h5.string(),
                                         "--format", "h5",      "--threads",     "1"};
  const pid_t a = start(args, temp.path() / "a.log"), b = start(args, temp.path() / "b.log");
  EXPECT_EQ(wait_for(a), 0) << text_of(temp.path() / "a.log.err");
  EXPECT_EQ(wait_for(b), 0) << text_of(temp.path() / "b.log.err");
  EXPECT_EQ(names_in(h5).size(), 24u);
  ASSERT_EQ(run(args, temp.path() / "c.log"), 0) << text_of(temp.path() / "c.log.err");
  EXPECT_NE(text_of(temp.path() / "c.log").find("0 extracted, 24 already done"), std::string::npos)
      << text_of(temp.path() / "c.log");
  EXPECT_FALSE(fs::exists(aief::io::lock_path_of(h5.string())));
}

TEST(OutputLock, TwoMergesIntoOneOutputAtOnceLoseNoImage) {
  // Before: `merge -o mm.h5 a.h5 b.h5 &` and `merge -o mm.h5 c.h5` both exited 0 and one of them
  // renamed its output over the other's (locking on or off).
  const TempFolder temp("aief_output_lock");
  std::vector<std::string> shards;
  for (const char* shard : {"a", "b", "c"}) {
    const fs::path images = image_folder(temp.path(), shard, 4);
    const std::string h5 = (temp.path() / (std::string(shard) + ".h5")).string();
    ASSERT_EQ(run({"extract", "--batch", images.string(), "-o", h5, "--format", "h5"},
                  temp.path() / "x.log"),
              0)
        << text_of(temp.path() / "x.log.err");
    shards.push_back(h5);
  }
  const fs::path merged = temp.path() / "mm.h5";
  for (int round = 0; round < 3; ++round) {
    fs::remove(merged);
    const pid_t first =
        start({"merge", "-o", merged.string(), shards[0], shards[1]}, temp.path() / "m1.log");
    const pid_t second = start({"merge", "-o", merged.string(), shards[2]}, temp.path() / "m2.log");
    EXPECT_EQ(wait_for(first), 0) << text_of(temp.path() / "m1.log.err");
    EXPECT_EQ(wait_for(second), 0) << text_of(temp.path() / "m2.log.err");
    EXPECT_EQ(names_in(merged).size(), 12u) << "round " << round;
  }
}

// A writer of each kind: what it needs made first, and its command.
struct Writer {
  const char* name;
  std::vector<std::string> (*command)(const fs::path& root, const fs::path& output);
};

std::vector<std::string> batch_command(const fs::path& root, const fs::path& output) {
  return {"extract",  "--batch", image_folder(root, "i", 3).string(), "-o", output.string(),
          "--format", "h5"};
}

std::vector<std::string> merge_command(const fs::path& root, const fs::path& output) {
  const std::string shard = (root / "s.h5").string();
  run({"extract", "--batch", image_folder(root, "s", 3).string(), "-o", shard, "--format", "h5"},
      root / "s.log");
  return {"merge", "-o", output.string(), shard};
}

std::vector<std::string> match_command(const fs::path& root, const fs::path& output) {
  const std::string features = (root / "f.h5").string();
  run({"extract", "--batch", image_folder(root, "p", 3).string(), "-o", features, "--format", "h5"},
      root / "f.log");
  std::ofstream(root / "pairs.txt") << "p0.png p1.png\np1.png p2.png\n";
  return {"match", "--pairs",      (root / "pairs.txt").string(), "--features", features,
          "-o",    output.string()};
}

void PrintTo(const Writer& writer, std::ostream* out) { *out << writer.name; }

class EveryWriter : public ::testing::TestWithParam<Writer> {};

TEST_P(EveryWriter, WaitsWhileAnotherHoldsTheLockAndSaysWho) {
  const TempFolder temp("aief_output_lock");
  const fs::path output = temp.path() / "out.h5", log = temp.path() / "w.log";
  const std::vector<std::string> command = GetParam().command(temp.path(), output);
  pid_t writer = -1;
  {
    const aief::io::OutputLock held(output.string());  // another writer, here
    writer = start(command, log);
    ASSERT_GT(writer, 0);
    // Until the writer says it waits (or ends, which it must not).
    int status = 0;
    bool ended = false;
    while (text_of(log.string() + ".err").find("waiting for process") == std::string::npos) {
      ended = waitpid(writer, &status, WNOHANG) == writer;
      if (ended) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_FALSE(ended) << "the writer did not wait for the lock: "
                        << text_of(log.string() + ".err");
    EXPECT_FALSE(fs::exists(output)) << "written while another held the lock";
    EXPECT_NE(text_of(log.string() + ".err").find("process " + std::to_string(getpid())),
              std::string::npos)
        << text_of(log.string() + ".err");
  }
  EXPECT_EQ(wait_for(writer), 0) << text_of(log.string() + ".err");
  EXPECT_TRUE(fs::exists(output));
  EXPECT_FALSE(fs::exists(aief::io::lock_path_of(output.string())));
}

TEST_P(EveryWriter, WithoutLocksOnTheFileSystemIsRefusedNamingTheFileAndTheSetting) {
  const TempFolder temp("aief_output_lock");
  const fs::path output = temp.path() / "out.h5", log = temp.path() / "w.log";
  const std::vector<std::string> command = GetParam().command(temp.path(), output);
  const std::string shim = std::string("LD_PRELOAD=") + AIEF_NO_LOCKS_SHIM;
  EXPECT_EQ(run(command, log, {shim}), 1);
  const std::string said = text_of(log.string() + ".err");
  EXPECT_NE(said.find("no lock can be had"), std::string::npos) << said;
  EXPECT_NE(said.find("'" + output.string() + "'"), std::string::npos) << said;
  EXPECT_NE(said.find("AIEF_FILE_LOCKING=FALSE"), std::string::npos) << said;
  EXPECT_NE(said.find("HDF5_USE_FILE_LOCKING"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(output));
  // The setting writes without the lock (the user knows no other run writes the file).
  EXPECT_EQ(run(command, log, {shim, "AIEF_FILE_LOCKING=FALSE"}), 0)
      << text_of(log.string() + ".err");
  EXPECT_TRUE(fs::exists(output));
}

INSTANTIATE_TEST_SUITE_P(OutputLock, EveryWriter,
                         ::testing::Values(Writer{"extract_batch", batch_command},
                                           Writer{"merge", merge_command},
                                           Writer{"match_pairs", match_command}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(OutputLock, OneProcessOpeningAFileTwiceForWritingIsRefusedNotDeadlocked) {
  const TempFolder temp("aief_output_lock");
  const std::string path = (temp.path() / "f.h5").string();
  aief::io::Hdf5File first(path, aief::io::Hdf5File::Mode::read_write);
  try {
    aief::io::Hdf5File second(path, aief::io::Hdf5File::Mode::read_write);
    ADD_FAILURE() << "opened twice for writing";
  } catch (const aief::Error& e) {
    EXPECT_NE(std::string(e.what()).find("open for writing already"), std::string::npos)
        << e.what();
  }
}

}  // namespace

#endif  // AIEF_HAVE_HDF5

// aief's own lock on the HDF5 outputs (io/output_lock.hpp): two CLI runs writing one file at once,
// with libhdf5's lock turned off (HDF5_USE_FILE_LOCKING=FALSE, as on Lustre and GPFS), leave a
// whole file; two merges into one output lose no image; a writer waits while the lock is held and
// says who holds it; where no lock can be had (a file system without fcntl locks:
// tests/no_locks_shim.cpp) the write is refused, naming the file and the setting.
#include <fcntl.h>
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
#include "tests/lock_run.hpp"
#include "tests/test_support.hpp"

#ifdef AIEF_HAVE_HDF5

namespace {

namespace fs = std::filesystem;
using aief::test::TempFolder;
using namespace aief::test::lock;  // start, run, wait_for, text_of, image_folder, How

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
  EXPECT_EQ(run(command, log, How{{shim}}), 1);
  const std::string said = text_of(log.string() + ".err");
  EXPECT_NE(said.find("no lock can be had"), std::string::npos) << said;
  const std::string quoted = std::string("'").append(output.string()).append("'");
  EXPECT_NE(said.find(quoted), std::string::npos) << said;
  EXPECT_NE(said.find("AIEF_FILE_LOCKING=FALSE"), std::string::npos) << said;
  EXPECT_NE(said.find("HDF5_USE_FILE_LOCKING"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(output));
  // The setting writes without the lock (the user knows no other run writes the file).
  EXPECT_EQ(run(command, log, How{{shim, "AIEF_FILE_LOCKING=FALSE"}}), 0)
      << text_of(log.string() + ".err");
  EXPECT_TRUE(fs::exists(output));
}

INSTANTIATE_TEST_SUITE_P(OutputLock, EveryWriter,
                         ::testing::Values(Writer{"extract_batch", batch_command},
                                           Writer{"merge", merge_command},
                                           Writer{"match_pairs", match_command}),
                         [](const auto& info) { return std::string(info.param.name); });

// A features file, a matches file of it and their pairs, written before a writer takes the lock.
struct ReadInputs {
  fs::path features, matches, pairs;
};
ReadInputs read_inputs(const fs::path& root) {
  ReadInputs inputs{root / "f.h5", root / "mt.h5", root / "pairs.txt"};
  const fs::path log = root / "made.log";
  EXPECT_EQ(run(batch_into(image_folder(root, "r", 3), inputs.features), log), 0)
      << text_of(log.string() + ".err");
  std::ofstream(inputs.pairs) << "r0.png r1.png\n";
  EXPECT_EQ(run({"match", "--pairs", inputs.pairs.string(), "--features-file",
                 inputs.features.string(), "-o", inputs.matches.string()},
                log),
            0)
      << text_of(log.string() + ".err");
  return inputs;
}

TEST(OutputLock, EveryReaderRefusesAFileItsWriterHoldsWithLibhdf5sLockOff) {
  // Before, with HDF5_USE_FILE_LOCKING=FALSE: `merge -o m.h5 rw.h5` during a batch into rw.h5
  // said "65 images merged" and colmap "65 images", both exit 0, as if the file were whole.
  const TempFolder temp("aief_output_lock");
  const ReadInputs in = read_inputs(temp.path());
  const fs::path log = temp.path() / "r.log";
  const std::vector<std::vector<std::string>> readers = {
      {"merge", "-o", temp.file("m.h5"), in.features.string()},
      {"colmap", "--features-file", in.features.string(), "--matches", in.matches.string(),
       "--pairs", in.pairs.string(), "-o", temp.file("c.db")},
      {"match", "--pairs", in.pairs.string(), "--features-file", in.features.string(), "-o",
       temp.file("m2.h5")}};
  {
    const aief::io::OutputLock writer(in.features.string());  // a writer at work, here
    for (const std::vector<std::string>& reader : readers) {
      EXPECT_EQ(run(reader, log), 1) << reader[0] << ": " << text_of(log.string() + ".err");
      const std::string said = text_of(log.string() + ".err");
      EXPECT_NE(said.find("cannot open '" + in.features.string() + "': it is locked by a writer"),
                std::string::npos)
          << said;
      EXPECT_NE(said.find("process " + std::to_string(getpid())), std::string::npos) << said;
    }
    EXPECT_FALSE(fs::exists(temp.file("m.h5")));
    EXPECT_FALSE(fs::exists(temp.file("m2.h5")));
  }
  for (const std::vector<std::string>& reader : readers)
    EXPECT_EQ(run(reader, log), 0) << reader[0] << ": " << text_of(log.string() + ".err");
  EXPECT_EQ(names_in(temp.file("m.h5")).size(), 3u);
}

TEST(OutputLock, AWriterWaitsWhileAReaderReadsWithLibhdf5sLockOff) {
  // Before: a batch into a file merge was reading wrote at once, under the reader's feet.
  const TempFolder temp("aief_output_lock");
  const fs::path images = image_folder(temp.path(), "w", 2), h5 = temp.path() / "f.h5";
  const fs::path log = temp.path() / "w.log";
  ASSERT_EQ(run(batch_into(images, h5), log), 0) << text_of(log.string() + ".err");
  fs::copy_file(images / "w0.png", images / "w9.png");  // something to write
  pid_t writer = -1;
  {
    const aief::io::Hdf5File reading(h5.string(), aief::io::Hdf5File::Mode::read);
    writer = start(batch_into(images, h5), log);
    bool ended = false;
    while (!ended && text_of(log.string() + ".err").find("waiting while another process reads") ==
                         std::string::npos) {
      int status = 0;
      ended = waitpid(writer, &status, WNOHANG) == writer;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_FALSE(ended) << "the writer did not wait: " << text_of(log.string() + ".err");
    EXPECT_EQ(reading.feature_names().size(), 2u);
  }
  EXPECT_EQ(wait_for(writer), 0) << text_of(log.string() + ".err");
  EXPECT_EQ(names_in(h5).size(), 3u);
  EXPECT_FALSE(fs::exists(aief::io::lock_path_of(h5.string())));
}

TEST(OutputLock, WithoutLocksAReaderSaysSoAndNamesLibhdf5sSettingNeverDamaged) {
  // NFS without its lock daemon answers ENOLCK: libhdf5's own lock fails. Before: "it is damaged
  // or cut short (libhdf5: No locks available); ... move it away and run that command again,
  // which writes it anew", of a good file; the writer named only AIEF_FILE_LOCKING=FALSE, which
  // then failed "cannot create 'w.h5': No locks available".
  const TempFolder temp("aief_output_lock");
  const ReadInputs in = read_inputs(temp.path());
  const fs::path log = temp.path() / "r.log";
  const std::string shim = std::string("LD_PRELOAD=") + AIEF_NO_LOCKS_SHIM;
  How without_locks{{shim, "AIEF_NO_LOCKS_ERRNO=ENOLCK"}, true};
  const std::vector<std::string> merge = {"merge", "-o", temp.file("m.h5"), in.features.string()};
  EXPECT_EQ(run(merge, log, without_locks), 1);
  std::string said = text_of(log.string() + ".err");
  EXPECT_EQ(said.find("damaged"), std::string::npos) << said;
  EXPECT_NE(said.find("no lock"), std::string::npos) << said;
  EXPECT_NE(said.find("AIEF_FILE_LOCKING=FALSE and HDF5_USE_FILE_LOCKING=FALSE"), std::string::npos)
      << said;
  // Following that advice in part, aief's lock off: libhdf5's own lock on the file read fails.
  without_locks.extra.push_back("AIEF_FILE_LOCKING=FALSE");
  const std::vector<std::string> match = {
      "match", "--pairs",         in.pairs.string(), "--features-file", in.features.string(),
      "-o",    temp.file("m2.h5")};
  EXPECT_EQ(run(match, log, without_locks), 1);
  said = text_of(log.string() + ".err");
  EXPECT_EQ(said.find("damaged"), std::string::npos) << said;
  EXPECT_NE(said.find("libhdf5 can have no lock on it"), std::string::npos) << said;
  EXPECT_NE(said.find("Set HDF5_USE_FILE_LOCKING=FALSE"), std::string::npos) << said;
  // The whole advice, followed, works.
  without_locks.extra.push_back("HDF5_USE_FILE_LOCKING=FALSE");
  EXPECT_EQ(run(match, log, without_locks), 0) << text_of(log.string() + ".err");
  EXPECT_EQ(run(merge, log, without_locks), 0) << text_of(log.string() + ".err");
}

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

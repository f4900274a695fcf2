// The temporaries every writer of io/ goes through (io/temporary_files.hpp): each write has its
// own, a killed write's is removed by the next run, one another run holds is never touched.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/temporary_files.hpp"
#include "tests/io_test_support.hpp"
#include "tests/test_support.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/hdf5_merge.hpp"
#endif

namespace aief {
namespace {

namespace fs = std::filesystem;
using OwnTempDir = test::TempFolder;

// A file of `text`, held locked as a writer in progress holds its temporary, until destroyed.
class HeldFile {
 public:
  HeldFile(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
    descriptor_ = ::open(path.c_str(), O_RDONLY);
    EXPECT_GE(descriptor_, 0) << path;
    EXPECT_EQ(::flock(descriptor_, LOCK_EX | LOCK_NB), 0) << path;
  }
  ~HeldFile() { ::close(descriptor_); }
  HeldFile(const HeldFile&) = delete;
  HeldFile& operator=(const HeldFile&) = delete;

 private:
  int descriptor_ = -1;
};

// A legal file name of 250 bytes has a temporary (name + ".tmp" would pass NAME_MAX), and a
// failed write leaves none behind.
TEST(AtomicWrite, LongNamesWorkAndAFailureLeavesNoTemporary) {
  OwnTempDir dir;
  const std::string long_name = dir.file(std::string(245, 'n') + ".json");  // 250 bytes
  io::write_file_atomically(long_name, "{}\n");
  EXPECT_TRUE(std::filesystem::exists(long_name));
  EXPECT_EQ(std::filesystem::path(io::temporary_path_of(long_name)).parent_path(), dir.path());
  EXPECT_EQ(io::temporary_path_of(long_name),
            io::temporary_path_of(long_name));  // a rerun finds it
  EXPECT_NE(io::temporary_path_of(dir.file("a.json")), io::temporary_path_of(dir.file("b.json")));
  std::filesystem::create_directories(dir.file("taken.json"));  // the rename onto a folder fails
  EXPECT_THROW(io::write_file_atomically(dir.file("taken.json"), "{}\n"), io::WriteError);
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    files += entry.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1u);  // the long-named output only
}

// Each write has a temporary of its own; a batch's sweep removes a killed write's (unlocked) and
// leaves one a writer holds locked (another process writing the same folder now).
TEST(AtomicWrite, EachWriteHasItsOwnTemporaryAndTheSweepKeepsLockedOnes) {
  OwnTempDir dir;
  const std::string output = dir.file("x.json");
  const std::string first = io::unique_temporary_path_of(output),
                    second = io::unique_temporary_path_of(output);
  EXPECT_NE(first, second);
  EXPECT_EQ(std::filesystem::path(first).parent_path(), dir.path());
  std::filesystem::create_directories(dir.file("sub"));
  const std::string killed = io::unique_temporary_path_of(dir.file("sub/y.json"));
  std::ofstream(killed) << "{";
  std::ofstream(first) << "{";
  const int held = ::open(first.c_str(), O_RDONLY);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);  // as write_file_atomically holds it
  std::ofstream(dir.file("notes.tmp")) << "not ours";
  EXPECT_EQ(io::remove_stale_temporaries(dir.path().string()), 1);
  EXPECT_FALSE(std::filesystem::exists(killed));
  EXPECT_TRUE(std::filesystem::exists(first)) << "a write in progress lost its temporary";
  EXPECT_TRUE(std::filesystem::exists(dir.file("notes.tmp")));
  ::close(held);
  io::write_file_atomically(output, "{}\n");
  EXPECT_TRUE(std::filesystem::exists(output));
}

// The stale temporaries of one output: a killed write's, an older aief's shared-name one and the
// journal of a killed COLMAP export go; one another run holds, the journal beside it and those of
// other outputs stay.
TEST(TemporaryFiles, RemovingOneOutputsStaleTemporariesKeepsHeldOnesAndOtherOutputs) {
  OwnTempDir dir;
  const std::string output = dir.file("out.h5");
  const std::string killed = io::unique_temporary_path_of(output);
  std::ofstream(killed) << "half";
  std::ofstream(io::temporary_path_of(output)) << "an older aief's";
  const std::string killed_export = io::unique_temporary_path_of(output);
  std::ofstream(killed_export + "-journal") << "journal";
  const std::string running = io::unique_temporary_path_of(output);
  const HeldFile held(running, "being written");
  std::ofstream(running + "-journal") << "its journal";
  const std::string other = io::unique_temporary_path_of(dir.file("other.h5"));
  std::ofstream(other) << "another output's";

  EXPECT_EQ(io::remove_stale_temporaries_of(output), 3);
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_FALSE(fs::exists(io::temporary_path_of(output)));
  EXPECT_FALSE(fs::exists(killed_export + "-journal"));
  EXPECT_TRUE(fs::exists(running)) << "a write in progress lost its temporary";
  EXPECT_TRUE(fs::exists(running + "-journal"));
  EXPECT_TRUE(fs::exists(other));
  EXPECT_EQ(io::remove_stale_temporaries_of(dir.file("missing/out.h5")), 0);
}

// A locked temporary becomes its output only where there is none (another run's stays), and
// leaves nothing behind when it does not.
TEST(TemporaryFiles, ALockedTemporaryNeverReplacesAnOutput) {
  OwnTempDir dir;
  const std::string output = dir.file("db.db");
  {
    io::LockedTemporary first(output);
    std::ofstream(first.path()) << "first";
    EXPECT_EQ(io::remove_stale_temporaries_of(output), 0) << "a held temporary was removed";
    io::LockedTemporary second(output);
    EXPECT_NE(first.path(), second.path());
    std::ofstream(second.path()) << "second";
    EXPECT_TRUE(second.rename_unless_output_exists());
    EXPECT_FALSE(first.rename_unless_output_exists());
  }
  std::ifstream in(output);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  EXPECT_THROW(io::LockedTemporary(dir.file("missing/db.db")), Error);
}

#ifdef AIEF_HAVE_HDF5
using test::sample_features;

// A merge removes a killed merge's temporary and leaves one another merge into the same output
// holds (was: one shared temporary name per output, removed or overwritten by the other run).
TEST(TemporaryFiles, AMergeLeavesAnotherMergesTemporaryAlone) {
  OwnTempDir dir;
  io::Hdf5File(dir.file("s0.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", sample_features("boat", 1));
  const std::string output = dir.file("out.h5");
  const std::string killed = io::unique_temporary_path_of(output);
  std::ofstream(killed) << "half";
  const std::string running = io::unique_temporary_path_of(output);
  const HeldFile held(running, "another merge's, being written");
  EXPECT_EQ(io::merge_feature_files(output, {dir.file("s0.h5")}), 1);
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_TRUE(fs::exists(running)) << "a merge in progress lost its temporary";
  EXPECT_TRUE(io::Hdf5File(output, io::Hdf5File::Mode::read).has_features("a.png"));
}

// A new HDF5 file is created under a temporary of its own: another run creating the same file
// keeps its temporary.
TEST(TemporaryFiles, ANewHdf5FileIsCreatedUnderATemporaryOfItsOwn) {
  OwnTempDir dir;
  const std::string output = dir.file("new.h5");
  const std::string running = io::unique_temporary_path_of(output);
  const HeldFile held(running, "another run's new file");
  const std::string older = io::temporary_path_of(output);  // an older aief's, still running
  const HeldFile held_by_older(older, "an older aief's new file");
  io::Hdf5File(output, io::Hdf5File::Mode::read_write)
      .write_features("a.png", sample_features("boat", 1));
  EXPECT_TRUE(fs::exists(running));
  EXPECT_TRUE(fs::exists(older));
  EXPECT_TRUE(io::Hdf5File(output, io::Hdf5File::Mode::read).has_features("a.png"));
}
#endif

}  // namespace
}  // namespace aief

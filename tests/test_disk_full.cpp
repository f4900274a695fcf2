// A full disk under every command that writes HDF5, COLMAP or per-image files, on a real small
// tmpfs (mounting needs root; CI runs as root, elsewhere these tests skip and say why). Each run
// must stop with exit 1 and aief's own message (no crash, no libhdf5 stack on stderr), keep every
// group complete before, leave no temporary behind, and resume once space is free.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include "tests/test_support.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif

namespace {

namespace fs = std::filesystem;

using CliResult = aief::test::CommandRun;  // status, and stdout + stderr

CliResult run(const std::string& arguments) {
  return aief::test::run_shell(std::string(AIEF_CLI_PATH) + " " + arguments);
}

// "i7.png": built by appending (GCC 12 warns falsely, -Wrestrict, on "i" + std::to_string(n)).
std::string numbered(const char* prefix, int n, const char* suffix) {
  std::string name(prefix);
  name.append(std::to_string(n)).append(suffix);
  return name;
}

// Exit 1 with aief's message for a full disk, and nothing from libhdf5.
void expect_clean_stop(const CliResult& r, const std::string& what) {
  EXPECT_EQ(r.status, 1) << what << "\n" << r.output;
  EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << what << "\n"
                                                                         << r.output;
  EXPECT_EQ(r.output.find("HDF5-DIAG"), std::string::npos) << what << "\n"
                                                           << r.output.substr(0, 2000);
}

// Files named like a temporary (io::temporary_path_of, SQLite's journal) or empty, below `folder`.
std::vector<std::string> leftovers(const fs::path& folder) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() &&
        (name.find(".tmp") != std::string::npos || fs::file_size(entry.path()) == 0))
      found.push_back(name);
  }
  return found;
}

// A tmpfs of 8 MB mounted on a folder of the test's own, unmounted at the end.
class DiskFull : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0)
      GTEST_SKIP() << "mounting a small tmpfs needs root (CI runs these as root)";
    disk_ = work_.path() / "disk";
    fs::create_directories(disk_);
    if (::mount("tmpfs", disk_.c_str(), "tmpfs", 0, "size=8m") != 0)
      GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
    mounted_ = true;
    // Images: the bundled samples, ten copies each under their own names.
    fs::create_directories(work_.path() / "images");
    std::ofstream list(work_.path() / "images.txt");
    int n = 0;
    for (const char* sequence : {"graf", "boat", "leuven"})
      for (const char* file : {"img1.png", "img2.png"})
        for (int copy = 0; copy < 10; ++copy) {
          const fs::path image = work_.path() / "images" / numbered("i", n++, ".png");
          fs::copy_file(aief::test::sample_path(sequence, file), image);
          list << image.string() << "\n";
        }
  }
  void TearDown() override {
    if (mounted_) ::umount2(disk_.c_str(), MNT_DETACH);
  }
  // Fills the disk but for `free_bytes`.
  void fill_leaving(std::uintmax_t free_bytes) {
    const fs::space_info space = fs::space(disk_);
    std::ofstream filler(disk_ / "filler", std::ios::binary);
    const std::string block(4096, 'x');
    for (std::uintmax_t written = 0; written + free_bytes + block.size() <= space.available;
         written += block.size())
      filler << block;
  }
  void free_space() { fs::remove(disk_ / "filler"); }

  aief::test::TempFolder work_{"aief_disk_full"};
  fs::path disk_;
  bool mounted_ = false;
};

#ifdef AIEF_HAVE_HDF5
// How many images a features file holds, every one of them read back whole.
int readable_images(const fs::path& h5) {
  const aief::io::Hdf5File file(h5.string(), aief::io::Hdf5File::Mode::read);
  int n = 0;
  for (const std::string& name : file.feature_names())
    n += file.read_features(name).keypoints.empty() ? 0 : 1;
  return n;
}

TEST_F(DiskFull, BatchH5StopsCleanlyKeepsWhatWasCompleteAndResumes) {
  const std::string list = (work_.path() / "images.txt").string(),
                    h5 = (disk_ / "features.h5").string();
  const std::string batch =
      "extract --batch " + list + " -o " + h5 + " --format h5 --features 2000 --threads 2";
  const std::string first = (work_.path() / "first.txt").string();
  {
    std::ifstream all(list);
    std::ofstream some(first);
    std::string line;
    for (int i = 0; i < 10 && std::getline(all, line); ++i) some << line << "\n";
  }
  ASSERT_EQ(run("extract --batch " + first + " -o " + h5 + " --format h5 --features 2000").status,
            0);
  fill_leaving(1 << 20);  // room for a few more images, not for 60
  const CliResult full = run(batch);
  expect_clean_stop(full, "batch into a full disk");
  EXPECT_NE(full.output.find("batch stopped:"), std::string::npos) << full.output;
  const int kept = readable_images(h5);
  EXPECT_GE(kept, 10);  // the ten complete before, and those written before the disk filled
  EXPECT_LT(kept, 60);
  EXPECT_TRUE(leftovers(disk_).empty());
  free_space();
  const CliResult resumed = run(batch);
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(kept) + " already done"), std::string::npos)
      << resumed.output;
  EXPECT_EQ(readable_images(h5), 60);
}

// The same on a file system without fallocate (the shim): the first images of a new file are
// kept, the file opens, and the rerun resumes as the message says.
TEST_F(DiskFull, BatchH5WithoutFallocateStopsCleanlyInItsFirstImagesAndResumes) {
  const std::string shim = std::string("LD_PRELOAD=") + AIEF_NO_FALLOCATE_SHIM + " ";
  ASSERT_NE(aief::test::run_shell(shim + "fallocate -l 1M " + (disk_ / "probe").string()).status, 0)
      << "the shim does not take fallocate away";
  fs::remove(disk_ / "probe");
  const std::string list = (work_.path() / "images.txt").string(),
                    h5 = (disk_ / "features.h5").string();
  const std::string batch =
      "extract --batch " + list + " -o " + h5 + " --format h5 --features 2000 --threads 2";
  fill_leaving(1 << 20);  // room for a few images, far from the first 64
  const CliResult full = aief::test::run_shell(shim + AIEF_CLI_PATH + " " + batch);
  expect_clean_stop(full, "batch into a full disk without fallocate");
  EXPECT_NE(full.output.find("run the same command again to resume"), std::string::npos)
      << full.output;
  int kept = -1;
  ASSERT_NO_THROW(kept = readable_images(h5)) << "the message says it resumes; the file must open";
  EXPECT_LT(kept, 60);
  // The images it says are done are those the file holds (before: every image written in memory
  // since the last flush too, "52 of 96 images are done" for a file holding 1).
  EXPECT_NE(full.output.find("batch stopped: " + std::to_string(kept) + " of 60 images are done"),
            std::string::npos)
      << full.output;
  EXPECT_TRUE(leftovers(disk_).empty());
  free_space();
  const CliResult resumed = aief::test::run_shell(shim + AIEF_CLI_PATH + " " + batch);
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(kept) + " already done"), std::string::npos)
      << resumed.output;
  EXPECT_EQ(readable_images(h5), 60);
}

// A disk already full when the file is created: the system's reason, and no empty file left.
TEST_F(DiskFull, BatchH5OnAFullDiskSaysSoAndLeavesNoFile) {
  const std::string list = (work_.path() / "images.txt").string(),
                    h5 = (disk_ / "features.h5").string();
  fill_leaving(0);
  const CliResult full =
      run("extract --batch " + list + " -o " + h5 + " --format h5 --features 2000");
  expect_clean_stop(full, "batch onto a disk already full");
  EXPECT_EQ(full.output.find("File exists"), std::string::npos) << full.output;
  EXPECT_FALSE(fs::exists(h5));
  EXPECT_TRUE(leftovers(disk_).empty());
}

TEST_F(DiskFull, MatchPairsStopsCleanlyAndResumes) {
  const std::string list = (work_.path() / "images.txt").string(),
                    features = (work_.path() / "features.h5").string();
  ASSERT_EQ(
      run("extract --batch " + list + " -o " + features + " --format h5 --features 2000").status,
      0);
  const std::string pairs = (work_.path() / "pairs.txt").string();
  {
    std::ofstream out(pairs);
    for (int i = 0; i < 60; ++i)
      for (int j = i + 1; j < 60; j += 17)
        out << (work_.path() / "images" / numbered("i", i, ".png")).string() << " "
            << (work_.path() / "images" / numbered("i", j, ".png")).string() << "\n";
  }
  const std::string matches = (disk_ / "matches.h5").string();
  const std::string match = "match --pairs " + pairs + " --features " + features + " -o " + matches;
  fill_leaving(256 << 10);
  expect_clean_stop(run(match), "match --pairs into a full disk");
  { const aief::io::Hdf5File readable(matches, aief::io::Hdf5File::Mode::read); }
  EXPECT_TRUE(leftovers(disk_).empty());
  free_space();
  const CliResult resumed = run(match);
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_EQ(resumed.output.find(" 0 already in"), std::string::npos)
      << resumed.output;  // some were kept
}

TEST_F(DiskFull, MergeLeavesTheOutputAsItWas) {
  const std::string list = (work_.path() / "images.txt").string();
  for (int shard = 0; shard < 2; ++shard)
    ASSERT_EQ(run("extract --batch " + list + " -o " +
                  (work_.path() / numbered("s", shard, ".h5")).string() +
                  " --format h5 --features 2000 --shard " + numbered("", shard, "/2"))
                  .status,
              0);
  const fs::path merged = disk_ / "features.h5";
  ASSERT_EQ(run("merge -o " + merged.string() + " " + (work_.path() / "s0.h5").string()).status, 0);
  const std::uintmax_t size = fs::file_size(merged);
  const int before = readable_images(merged);
  fill_leaving(512 << 10);
  const CliResult full =
      run("merge -o " + merged.string() + " " + (work_.path() / "s1.h5").string());
  expect_clean_stop(full, "merge into a full disk");
  // One account of the output: left as it was. Was: also "what was complete before is kept",
  // said of the temporary the merge then removed.
  EXPECT_NE(full.output.find("left as it was"), std::string::npos) << full.output;
  EXPECT_EQ(full.output.find("what was complete before is kept"), std::string::npos) << full.output;
  EXPECT_EQ(fs::file_size(merged), size);
  EXPECT_EQ(readable_images(merged), before);
  EXPECT_EQ(leftovers(disk_), std::vector<std::string>{});
}

// A whole .h5 on a read-only file system was called "damaged or cut short ... move it away".
TEST_F(DiskFull, AWholeFileOnAReadOnlyFileSystemSaysSoAndThatItIsWhole) {
  const fs::path h5 = disk_ / "whole.h5";
  {
    aief::io::Hdf5File file(h5.string(), aief::io::Hdf5File::Mode::read_write);
    file.close();
  }
  ASSERT_EQ(::mount(nullptr, disk_.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr), 0)
      << std::strerror(errno);
  std::string message;
  try {
    aief::io::Hdf5File(h5.string(), aief::io::Hdf5File::Mode::read_write);
  } catch (const std::exception& e) {
    message = e.what();
  }
  ::mount(nullptr, disk_.c_str(), nullptr, MS_REMOUNT, nullptr);
  EXPECT_NE(message.find("it is on a read-only file system"), std::string::npos) << message;
  EXPECT_NE(message.find("the file itself is whole"), std::string::npos) << message;
  EXPECT_EQ(message.find("damaged"), std::string::npos) << message;
}

#ifdef AIEF_HAVE_COLMAP_EXPORT
// A guard, not a reproduction: the COLMAP export already removed its temporary on failure, and
// SQLite deletes its rollback journal when the connection closes after a failed write (tried on
// a tmpfs with 0 to 16 pages free: never a journal left), so this passes on the code before the
// temporaries were reworked too.
TEST_F(DiskFull, ColmapLeavesNoDatabaseNorTemporary) {
  const std::string list = (work_.path() / "images.txt").string(),
                    features = (work_.path() / "features.h5").string();
  ASSERT_EQ(
      run("extract --batch " + list + " -o " + features + " --format h5 --features 2000").status,
      0);
  const std::string pairs = (work_.path() / "pairs.txt").string(),
                    matches = (work_.path() / "matches.h5").string();
  std::ofstream(pairs) << (work_.path() / "images/i0.png").string() << " "
                       << (work_.path() / "images/i1.png").string() << "\n";
  ASSERT_EQ(run("match --pairs " + pairs + " --features " + features + " -o " + matches).status, 0);
  fill_leaving(64 << 10);
  const CliResult r = run("colmap --features " + features + " --matches " + matches + " --pairs " +
                          pairs + " -o " + (disk_ / "db.db").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_FALSE(fs::exists(disk_ / "db.db"));
  EXPECT_EQ(leftovers(disk_), std::vector<std::string>{});
}
#endif
#endif

TEST_F(DiskFull, FilePerImageBatchStopsAndLeavesNoTemporaries) {
  const std::string list = (work_.path() / "images.txt").string(), out = (disk_ / "out").string();
  fill_leaving(1 << 20);
  const CliResult full = run("extract --batch " + list + " -o " + out + " --features 2000");
  expect_clean_stop(full, "json batch into a full disk");
  EXPECT_NE(full.output.find("batch stopped:"), std::string::npos) << full.output;
  EXPECT_EQ(leftovers(disk_ / "out"), std::vector<std::string>{});
}

}  // namespace

// The HDF5 feature and match files (hloc layout) at the C++ level, so the sanitizer builds run
// them: open failures said in words a user acts on, groups of every name, hloc's pair groups
// (merging shards: tests/test_hdf5_merge.cpp); python/tests/ reads the same files back with h5py.
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "tests/io_test_support.hpp"
#include "tests/odd_names.hpp"
#include "tests/test_support.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif

namespace aief {
namespace {

// A folder of this test's own, removed at the end.
using OwnTempDir = test::TempFolder;
using test::expect_same;
using test::sample_features;

#ifdef AIEF_HAVE_HDF5
// Why an HDF5 file cannot be opened, in words a user acts on (not "damaged, or not HDF5?", which
// invites deleting a good file that another process holds).
TEST(Hdf5Features, OpenFailuresSayWhich) {
  OwnTempDir dir;
  const auto message = [](const std::function<void()>& open) {
    try {
      open();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  using Mode = io::Hdf5File::Mode;
  EXPECT_NE(message([&] {
              io::Hdf5File(dir.file("none/f.h5"), Mode::read_write);
            }).find("the folder '" + dir.file("none") + "' does not exist"),
            std::string::npos);
  std::filesystem::create_directories(dir.file("folder.h5"));
  EXPECT_NE(message([&] {
              io::Hdf5File(dir.file("folder.h5"), Mode::read_write);
            }).find("it is a directory"),
            std::string::npos);
  std::ofstream(dir.file("text.h5")) << "text";
  EXPECT_NE(message([&] {
              io::Hdf5File(dir.file("text.h5"), Mode::read_write);
            }).find("it is not an HDF5 file"),
            std::string::npos);
  io::Hdf5File(dir.file("good.h5"), Mode::read_write)
      .write_features("a.png", sample_features("boat", 1));
  {
    const int held =
        ::open(dir.file("good.h5").c_str(), O_RDONLY);  // as libhdf5 locks a file it writes
    ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
    EXPECT_NE(message([&] {
                io::Hdf5File(dir.file("good.h5"), Mode::read_write);
              }).find("it is locked by a writer"),
              std::string::npos);
    // A reader too (merge, match --pairs and colmap reading a shard still being written).
    for (const Mode reading : {Mode::read, Mode::read_in_name_order})
      EXPECT_NE(message([&] {
                  io::Hdf5File(dir.file("good.h5"), reading);
                }).find("it is locked by a writer"),
                std::string::npos);
    ::close(held);
  }
  std::filesystem::copy_file(dir.file("good.h5"), dir.file("cut.h5"));
  std::filesystem::resize_file(dir.file("cut.h5"),
                               std::filesystem::file_size(dir.file("cut.h5")) / 2);
  const std::string cut = message([&] { io::Hdf5File(dir.file("cut.h5"), Mode::read); });
  EXPECT_NE(cut.find("it is damaged or cut short (libhdf5: truncated file"), std::string::npos)
      << cut;
  EXPECT_NE(cut.find("run that command again"), std::string::npos) << cut;
}

// A whole file that cannot be opened for writing (another handle holds it, no permission, a
// read-only file system) was called "damaged or cut short ... move it away". Now the reason, and
// that the file is whole.
TEST(Hdf5Features, AWholeFileThatCannotBeWrittenSaysWhyAndThatItIsWhole) {
  OwnTempDir dir;
  using Mode = io::Hdf5File::Mode;
  const std::string path = dir.file("whole.h5");
  io::Hdf5File(path, Mode::read_write).write_features("a.png", sample_features("boat", 1));
  const auto message = [&] {
    try {
      io::Hdf5File(path, Mode::read_write);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("opened");
  };
  {
    const io::Hdf5File reader(path, Mode::read);  // as an h5py.File or FeaturesFile left open
    const std::string held = message();
    EXPECT_NE(held.find("another handle holds it open"), std::string::npos) << held;
    EXPECT_NE(held.find("the file itself is whole"), std::string::npos) << held;
    EXPECT_EQ(held.find("damaged"), std::string::npos) << held;
  }
  if (::geteuid() != 0) {  // root writes a file of mode 444 all the same
    std::filesystem::permissions(path, std::filesystem::perms::owner_read |
                                           std::filesystem::perms::group_read |
                                           std::filesystem::perms::others_read);
    const std::string denied = message();
    EXPECT_NE(denied.find("you have no permission to write it"), std::string::npos) << denied;
    EXPECT_NE(denied.find("the file itself is whole"), std::string::npos) << denied;
  }
}

TEST(Hdf5Features, RoundTripInNestedGroupsAndResume) {
  OwnTempDir dir;
  const Features a = sample_features("graf", 1), empty{};
  {
    io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
    EXPECT_FALSE(file.has_features("sub/img1.png"));
    file.write_features("sub/img1.png", a);
    file.write_features("flat.png", empty);
    file.write_features("sub/img1.png", a);  // rewriting replaces the group
  }
  const io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read);
  EXPECT_TRUE(file.has_features("sub/img1.png"));
  EXPECT_FALSE(file.has_features("sub"));
  EXPECT_EQ(file.feature_names(), (std::vector<std::string>{"flat.png", "sub/img1.png"}));
  expect_same(file.read_features("sub/img1.png"), a);
  EXPECT_TRUE(file.read_features("flat.png").keypoints.empty());
  EXPECT_THROW(file.read_features("none.png"), Error);
}

TEST(Hdf5Features, NamesSpelledWithExtraSlashesFindTheirGroupsAfterAReopen) {
  // A written file keeps the names of its groups in memory; libhdf5 reads "b//c" as the group
  // "b/c", and so must that index, or a resumed batch takes its images as missing and fails on
  // "name already exists".
  OwnTempDir dir;
  const Features a = sample_features("graf", 1);
  {
    io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
    file.write_features("/abs/a.png", a);
    EXPECT_TRUE(file.has_features("/abs/a.png"));
    file.write_features("b//c.png", a);
    EXPECT_TRUE(file.has_features("b/c.png"));
    io::Hdf5File matches(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
    matches.write_matches("/abs/a.png", "b/c.png", 3, {{0, 1, 2}});
  }
  io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
  EXPECT_TRUE(file.has_features("/abs/a.png"));
  EXPECT_TRUE(file.has_features("b//c.png"));
  EXPECT_FALSE(file.has_features("abs/b.png"));
  EXPECT_NO_THROW(file.write_features("/abs/a.png", a));
  EXPECT_EQ(file.feature_names(), (std::vector<std::string>{"/abs/a.png", "b/c.png"}));
  io::Hdf5File matches(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
  EXPECT_TRUE(matches.has_matches("/abs/a.png", "b/c.png"));
  EXPECT_NO_THROW(matches.write_matches("/abs/a.png", "b/c.png", 3, {{0, 1, 2}}));
}

// A name libhdf5 reads as the group holding it ("."; "x/.") is refused before anything is written,
// so it neither breaks the file for the writes after it nor loses those before it (it did: the
// half-done group failed the whole object, and the writes since the last flush were lost).
TEST(Hdf5Features, ANameEndingInDotIsRefusedAndTheWritesAroundItAreKept) {
  OwnTempDir dir;
  const Features a = sample_features("graf", 1);
  {
    io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
    for (const char* name : {"a.png", "b.png", "x/c.png"}) file.write_features(name, a);
    for (const char* name : {".", "./", "x/.", "x/./", "/."}) {
      try {
        file.write_features(name, a);
        ADD_FAILURE() << "'" << name << "' was written";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nothing was written for it"), std::string::npos)
            << e.what();
      }
    }
    file.write_features("d.png", a);
    file.write_features("y/", a);  // libhdf5 reads it as "y": a group of its own
  }
  const io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read);
  EXPECT_EQ(file.feature_names(),
            (std::vector<std::string>{"a.png", "b.png", "d.png", "x/c.png", "y"}));
  expect_same(file.read_features("x/c.png"), a);
}

// "/data/q/x.png" and "data/q/x.png" are two files: two groups, as the JSON layout's two files
// ("%2F/data/q/x.png.json"); a name of a leading '%' keeps its own group too. Other names are
// their groups, byte for byte (hloc reads them).
TEST(Hdf5Features, AnAbsoluteNameAndItsRelativeTwinHaveGroupsOfTheirOwn) {
  OwnTempDir dir;
  const Features a = sample_features("graf", 1), b = sample_features("boat", 1),
                 c = sample_features("leuven", 1);
  for (int reopen = 0; reopen < 2; ++reopen) {
    io::Hdf5File file(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
    if (reopen == 0) {
      file.write_features("/data/q/x.png", a);
      file.write_features("data/q/x.png", b);
      file.write_features("%2F/data/q/x.png", c);
    }
    EXPECT_EQ(file.read_features("/data/q/x.png").keypoints.size(), a.keypoints.size());
    EXPECT_EQ(file.read_features("data/q/x.png").keypoints.size(), b.keypoints.size());
    EXPECT_EQ(file.read_features("%2F/data/q/x.png").keypoints.size(), c.keypoints.size());
    EXPECT_EQ(file.feature_names(),
              (std::vector<std::string>{"%2F/data/q/x.png", "/data/q/x.png", "data/q/x.png"}));
  }
  EXPECT_EQ(io::image_group("/data/q/x.png"), "%2F/data/q/x.png");
  EXPECT_EQ(io::image_group("%2F/data/q/x.png"), "%252F/data/q/x.png");
  EXPECT_EQ(io::image_group("sub/a%2F.png"), "sub/a%2F.png");
  for (const std::string& name : aief::test::odd_image_names())
    EXPECT_EQ(io::image_of_group(io::image_group(name)), name) << name;
}

TEST(Hdf5Features, MatchesInHlocPairGroups) {
  OwnTempDir dir;
  EXPECT_EQ(io::hloc_pair_name("a/b.png", "c.png"), "a-b.png/c.png");
  const std::vector<Match> matches = {{0, 5, 10}, {3, 1, 0}, {4, 2, 256}};
  {
    io::Hdf5File file(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
    file.write_matches("a/b.png", "c.png", 6, matches);
  }
  const io::Hdf5File file(dir.file("m.h5"), io::Hdf5File::Mode::read);
  EXPECT_TRUE(file.has_matches("a/b.png", "c.png"));
  EXPECT_FALSE(file.has_matches("c.png", "a/b.png"));
  EXPECT_FALSE(file.find_matches("c.png", "a/b.png"));
  EXPECT_FALSE(file.find_matches("a/b.png", "d.png"));  // the first image's pairs, not this one
  EXPECT_THROW(file.read_matches("a/b.png", "d.png"), Error);
  // Another pair of the same hloc group is refused, both pairs named, never given these matches.
  for (const auto& ask :
       {std::function<void()>([&] { (void)file.has_matches("a-b.png", "c.png"); }),
        std::function<void()>([&] { (void)file.read_matches("a-b.png", "c.png"); }),
        std::function<void()>([&] { (void)file.find_matches("a-b.png", "c.png"); })}) {
    try {
      ask();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(
          std::string(e.what()).find(
              "pair 'a-b.png c.png' and pair 'a/b.png c.png' share the group 'a-b.png/c.png'"),
          std::string::npos)
          << e.what();
    }
  }
  const std::vector<Match> back = file.read_matches("a/b.png", "c.png");
  ASSERT_EQ(back.size(), matches.size());
  for (std::size_t i = 0; i < matches.size(); ++i) {
    EXPECT_EQ(back[i].query, matches[i].query);
    EXPECT_EQ(back[i].train, matches[i].train);
    EXPECT_EQ(back[i].distance, matches[i].distance);
  }
  const std::optional<std::vector<Match>> found = file.find_matches("a/b.png", "c.png");
  ASSERT_TRUE(found);
  ASSERT_EQ(found->size(), matches.size());
  for (std::size_t i = 0; i < matches.size(); ++i) EXPECT_EQ((*found)[i].train, matches[i].train);
}

// What is written or replaced after a pair lookup is seen by the next one, and a file looked up
// in closes for real.
TEST(Hdf5Features, PairLookupsSeeWritesMadeBetweenThem) {
  OwnTempDir dir;
  {
    io::Hdf5File file(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
    file.write_matches("a.png", "b.png", 4, {{0, 1, 0}});
    EXPECT_TRUE(file.has_matches("a.png", "b.png"));
    EXPECT_FALSE(file.has_matches("a.png", "c.png"));
    file.write_matches("a.png", "c.png", 4, {{1, 2, 0}});
    EXPECT_TRUE(file.has_matches("a.png", "c.png"));
    EXPECT_EQ(file.read_matches("a.png", "c.png").at(0).train, 2);
    file.write_matches("a.png", "c.png", 4, {{1, 3, 0}});  // replaced
    EXPECT_EQ(file.read_matches("a.png", "c.png").at(0).train, 3);
    file.close();
  }
  io::Hdf5File reopened(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
  EXPECT_EQ(reopened.read_matches("a.png", "b.png").at(0).train, 1);
  EXPECT_EQ(reopened.read_matches("a.png", "c.png").at(0).train, 3);
  EXPECT_FALSE(reopened.find_matches("b.png", "a.png"));
}
#endif

}  // namespace
}  // namespace aief

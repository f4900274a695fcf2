// HDF5 (hloc layout), npz and COLMAP writers at the C++ level, so the sanitizer builds run them;
// python/tests/ reads the same files back with h5py, numpy, sqlite3 and colmap.
#include <cstdlib>
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
#include "aief/extractor.hpp"
#include "aief/match.hpp"
#include "io/image_io.hpp"
#include "io/json_writer.hpp"
#include "io/npz_writer.hpp"
#include "io/pairs_file.hpp"
#include "tests/odd_names.hpp"
#include "tests/test_support.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/hdf5_merge.hpp"
#endif
#ifdef AIEF_HAVE_COLMAP_EXPORT
#include "io/colmap_database.hpp"
#endif

namespace aief {
namespace {

// A folder of this test's own, removed at the end.
using OwnTempDir = test::TempFolder;

Features sample_features(const char* sequence, int index) {
  const GrayImage image =
      io::read_gray_image(test::sample_path(sequence, "img" + std::to_string(index) + ".png"));
  return extract(image.view());
}

// The hidden temporaries (io/temporary_files.hpp) left in `folder`.
std::vector<std::string> temporaries_in(const std::string& folder) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name[0] == '.' && name.find(".tmp") != std::string::npos) found.push_back(name);
  }
  return found;
}

void expect_same(const Features& a, const Features& b) {
  ASSERT_EQ(a.keypoints.size(), b.keypoints.size());
  EXPECT_EQ(a.image_width, b.image_width);
  EXPECT_EQ(a.image_height, b.image_height);
  for (std::size_t i = 0; i < a.keypoints.size(); ++i) {
    EXPECT_EQ(a.keypoints[i].x, b.keypoints[i].x) << i;
    EXPECT_EQ(a.keypoints[i].y, b.keypoints[i].y) << i;
    EXPECT_EQ(a.keypoints[i].size, b.keypoints[i].size) << i;
    EXPECT_EQ(a.keypoints[i].angle_deg, b.keypoints[i].angle_deg) << i;
    EXPECT_EQ(a.keypoints[i].response, b.keypoints[i].response) << i;
    EXPECT_EQ(a.keypoints[i].octave, b.keypoints[i].octave) << i;
  }
  EXPECT_EQ(a.descriptors, b.descriptors);
}

TEST(NpzWriter, ArchiveOfNpyArraysWithNumpyHeaders) {
  const Features features = sample_features("boat", 1);
  const std::string npz = io::features_npz(features, ExtractorOptions{});
  EXPECT_EQ(npz.substr(0, 4), std::string("PK\x03\x04", 4));
  EXPECT_EQ(npz.substr(npz.size() - 22, 4),
            std::string("PK\x05\x06", 4));  // end of central directory, no comment
  const std::string n = std::to_string(features.keypoints.size());
  for (const std::string& header :
       {"{'descr': '<f4', 'fortran_order': False, 'shape': (" + n + ", 2), }",
        "{'descr': '|u1', 'fortran_order': False, 'shape': (" + n + ", 32), }",
        "{'descr': '<i4', 'fortran_order': False, 'shape': (" + n + ",), }",
        std::string("{'descr': '<i8', 'fortran_order': False, 'shape': (2,), }")})
    EXPECT_NE(npz.find(header), std::string::npos) << header;
  // Every .npy header is padded so its data starts 64-byte aligned within the member.
  const std::size_t magic = npz.find("\x93NUMPY");
  ASSERT_NE(magic, std::string::npos);
  const std::size_t header_length = static_cast<unsigned char>(npz[magic + 8]) |
                                    (static_cast<unsigned char>(npz[magic + 9]) << 8);
  EXPECT_EQ((10 + header_length) % 64, 0u);
  EXPECT_EQ(npz[magic + 10 + header_length - 1], '\n');
}

TEST(PairsFile, ReadsNamesSkipsCommentsAndNamesBadLines) {
  OwnTempDir dir;
  std::ofstream(dir.file("pairs.txt")) << "# comment\na.png b.png\n\n  c/d.png e.png  \n";
  const io::PairsList pairs = io::read_pairs(dir.file("pairs.txt"));
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs.pair(1), io::ImagePair("c/d.png", "e.png"));
  // Each name held once, the pairs as indices into them (a collection's list in little memory).
  std::ofstream(dir.file("chain.txt")) << "a.png b.png\nb.png c.png\nc.png a.png\n";
  const io::PairsList chain = io::read_pairs(dir.file("chain.txt"));
  EXPECT_EQ(chain.names, (std::vector<std::string>{"a.png", "b.png", "c.png"}));
  using Indices = std::pair<std::uint32_t, std::uint32_t>;
  EXPECT_EQ(chain.pairs, (std::vector<Indices>{{0, 1}, {1, 2}, {2, 0}}));
  std::ofstream(dir.file("bad.txt")) << "a.png b.png\na.png b.png c.png\n";
  try {
    io::read_pairs(dir.file("bad.txt"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2: expected two image names"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(io::read_pairs(dir.file("missing.txt")), Error);
}

// hloc's pairs files have no comments, so what is skipped is said; a self-pair is no pair.
TEST(PairsFile, SaysWhatItSkipsAndRefusesPairsSharingAGroup) {
  OwnTempDir dir;
  std::ofstream(dir.file("pairs.txt")) << "#a.png b.png\na.png a.png\na.png b.png\na.png b.png\n";
  const io::PairsList list = io::read_pairs(dir.file("pairs.txt"));
  ASSERT_EQ(list.pairs.size(), 1u);
  ASSERT_EQ(list.notes.size(), 2u);
  EXPECT_NE(list.notes[0].find("line 1 skipped: it begins with '#'"), std::string::npos)
      << list.notes[0];
  EXPECT_NE(list.notes[1].find("line 2 skipped: 'a.png' paired with itself"), std::string::npos)
      << list.notes[1];
  std::ofstream(dir.file("collide.txt")) << "a/b.png c.png\na-b.png c.png\n";
  try {
    io::read_pairs(dir.file("collide.txt"));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("line 2 ('a-b.png c.png') and line 1 ('a/b.png c.png')"),
              std::string::npos)
        << message;
  }
}

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

// A failed merge (an image in two inputs, a missing, cut or non-HDF5 input) leaves the output
// as it was, or absent, and no temporary.
TEST(Hdf5Features, FailedMergeLeavesTheOutputAsItWas) {
  OwnTempDir dir;
  const Features a = sample_features("boat", 1), b = sample_features("boat", 2);
  io::Hdf5File(dir.file("s0.h5"), io::Hdf5File::Mode::read_write).write_features("a.png", a);
  io::Hdf5File(dir.file("s1.h5"), io::Hdf5File::Mode::read_write).write_features("b.png", b);
  io::Hdf5File(dir.file("s2.h5"), io::Hdf5File::Mode::read_write).write_features("b.png", b);
  std::filesystem::copy_file(dir.file("s1.h5"), dir.file("cut.h5"));
  std::filesystem::resize_file(dir.file("cut.h5"),
                               std::filesystem::file_size(dir.file("cut.h5")) / 2);
  std::ofstream(dir.file("text.h5")) << "text";
  ASSERT_EQ(io::merge_feature_files(dir.file("out.h5"), {dir.file("s0.h5")}), 1);
  const auto bytes_of = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string before = bytes_of(dir.file("out.h5"));
  for (const char* bad : {"s2.h5", "cut.h5", "text.h5", "missing.h5"}) {
    EXPECT_THROW(io::merge_feature_files(dir.file("out.h5"), {dir.file("s1.h5"), dir.file(bad)}),
                 Error)
        << bad;
    EXPECT_EQ(bytes_of(dir.file("out.h5")), before) << bad;
    EXPECT_THROW(io::merge_feature_files(dir.file("new.h5"), {dir.file("s1.h5"), dir.file(bad)}),
                 Error)
        << bad;
    EXPECT_FALSE(std::filesystem::exists(dir.file("new.h5"))) << bad;
  }
  EXPECT_EQ(temporaries_in(dir.path().string()), std::vector<std::string>{});
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

// A merge run again after a shard's image changed, or after the shards were extracted again with
// other options, replaces what the output held of those images; an unchanged rerun copies none.
TEST(Hdf5Features, MergeRerunReplacesGroupsWhoseShardImageOrOptionsChanged) {
  OwnTempDir dir;
  const Features a = sample_features("boat", 1), b = sample_features("boat", 2),
                 changed = sample_features("graf", 1);
  io::SourceRecord source, later;
  source.name = later.name = "a.png";
  source.bytes = 100;
  later.bytes = 120;
  ExtractorOptions options, other;
  other.n_features = options.n_features + 500;
  {
    io::Hdf5File shard(dir.file("s0.h5"), io::Hdf5File::Mode::read_write);
    shard.write_features("a.png", a, &source, &options);
    shard.write_features("b.png", b, &source, &options);
  }
  int replaced = -1;
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("s0.h5")}, &replaced), 2);
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("s0.h5")}, &replaced), 0);
  EXPECT_EQ(replaced, 0);
  // The image a.png changed; its shard was brought up to date.
  io::Hdf5File(dir.file("s0.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", changed, &later, &options);
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("s0.h5")}, &replaced), 1);
  EXPECT_EQ(replaced, 1);
  expect_same(io::Hdf5File(dir.file("all.h5"), io::Hdf5File::Mode::read).read_features("a.png"),
              changed);
  // Extracted again with other options, every image.
  {
    io::Hdf5File shard(dir.file("s0.h5"), io::Hdf5File::Mode::read_write);
    shard.write_features("a.png", b, &later, &other);
    shard.write_features("b.png", a, &source, &other);
  }
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("s0.h5")}, &replaced), 2);
  EXPECT_EQ(replaced, 2);
  {
    const io::Hdf5File all(dir.file("all.h5"), io::Hdf5File::Mode::read);
    expect_same(all.read_features("a.png"), b);
    expect_same(all.read_features("b.png"), a);
  }
  // Only one image of the output extracted again with other options: the rest would disagree.
  io::Hdf5File(dir.file("s1.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", a, &later, &options);
  EXPECT_THROW(io::merge_feature_files(dir.file("all.h5"), {dir.file("s1.h5")}), Error);
}

// An older shard (its groups of an older file of the image) never replaces the newer group the
// output holds, and says so; a matches file is no shard (before: an empty output, exit 0).
TEST(Hdf5Features, MergeKeepsTheNewerGroupAndRefusesAMatchesFile) {
  OwnTempDir dir;
  const Features old_a = sample_features("boat", 1), new_a = sample_features("graf", 1);
  io::SourceRecord older, newer;
  older.name = newer.name = "a.png";
  older.bytes = newer.bytes = 100;
  older.mtime_ns = 1000;
  newer.mtime_ns = 2000;
  const ExtractorOptions options;
  io::Hdf5File(dir.file("old.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", old_a, &older, &options);
  io::Hdf5File(dir.file("new.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", new_a, &newer, &options);
  int replaced = -1;
  std::vector<std::string> notes;
  ASSERT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("new.h5")}, &replaced, &notes), 1);
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("old.h5")}, &replaced, &notes), 0);
  EXPECT_EQ(replaced, 0);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("1 image(s) kept as '" + dir.file("all.h5") + "' holds them"),
            std::string::npos)
      << notes[0];
  EXPECT_NE(notes[0].find("'a.png' ('" + dir.file("old.h5") + "')"), std::string::npos) << notes[0];
  expect_same(io::Hdf5File(dir.file("all.h5"), io::Hdf5File::Mode::read).read_features("a.png"),
              new_a);
  // The newer shard still replaces an older group.
  io::Hdf5File(dir.file("all.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", old_a, &older, &options);
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("new.h5")}, &replaced), 1);
  EXPECT_EQ(replaced, 1);

  {
    io::Hdf5File matches(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
    matches.write_matches("a.png", "b.png", 3, {{0, 1, 10}});
  }
  try {
    io::merge_feature_files(dir.file("mm.h5"), {dir.file("m.h5")});
    ADD_FAILURE() << "a matches file merged";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds matches (pair groups with matches0), not features"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("mm.h5")));
  EXPECT_THROW(io::merge_feature_files(dir.file("m.h5"), {dir.file("new.h5")}), Error);
}

TEST(Hdf5Features, MergeCopiesShardsAndRefusesAnImageTwice) {
  OwnTempDir dir;
  const Features a = sample_features("boat", 1), b = sample_features("boat", 2);
  io::Hdf5File(dir.file("s0.h5"), io::Hdf5File::Mode::read_write).write_features("x/a.png", a);
  io::Hdf5File(dir.file("s1.h5"), io::Hdf5File::Mode::read_write).write_features("b.png", b);
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("s0.h5"), dir.file("s1.h5")}), 2);
  EXPECT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("s0.h5")}),
            0);  // already there: kept
  {
    const io::Hdf5File all(dir.file("all.h5"), io::Hdf5File::Mode::read);
    expect_same(all.read_features("x/a.png"), a);
    expect_same(all.read_features("b.png"), b);
  }
  EXPECT_THROW(
      io::merge_feature_files(dir.file("twice.h5"), {dir.file("s0.h5"), dir.file("s0.h5")}), Error);
  EXPECT_THROW(io::merge_feature_files(dir.file("x.h5"), {dir.file("missing.h5")}), Error);
  std::ofstream(dir.file("not.h5")) << "text";
  EXPECT_THROW(io::Hdf5File(dir.file("not.h5"), io::Hdf5File::Mode::read), Error);
}
#endif

#ifdef AIEF_HAVE_COLMAP_EXPORT
TEST(ColmapDatabase, WritesOnceAndNamesWhatIsMissing) {
  OwnTempDir dir;
  const Features a = sample_features("graf", 1), b = sample_features("graf", 2);
  {
    io::Hdf5File features(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
    features.write_features("a.png", a);
    features.write_features("b.png", b);
    io::Hdf5File matches(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
    matches.write_matches("b.png", "a.png", static_cast<int>(b.keypoints.size()),
                          match_descriptors(b.descriptors, a.descriptors));
  }
  std::ofstream(dir.file("pairs.txt")) << "a.png b.png\n";  // stored the other way round
  const io::ColmapExport done = io::export_colmap_database(dir.file("db.db"), dir.file("f.h5"),
                                                           dir.file("m.h5"), dir.file("pairs.txt"));
  EXPECT_EQ(done.images, 2);
  EXPECT_EQ(done.pairs, 1);
  EXPECT_EQ(done.matches,
            static_cast<long long>(match_descriptors(b.descriptors, a.descriptors).size()));
  EXPECT_THROW(io::export_colmap_database(dir.file("db.db"), dir.file("f.h5"), dir.file("m.h5"),
                                          dir.file("pairs.txt")),
               Error);
  std::ofstream(dir.file("unknown.txt")) << "a.png c.png\n";
  EXPECT_THROW(io::export_colmap_database(dir.file("db2.db"), dir.file("f.h5"), dir.file("m.h5"),
                                          dir.file("unknown.txt")),
               Error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("db2.db")));
  EXPECT_EQ(temporaries_in(dir.path().string()), std::vector<std::string>{});
}

// Matches from another run (more keypoints than the features file holds) are refused, the pair
// and the image named; a self-pair is left out with a note.
TEST(ColmapDatabase, RefusesMatchIndicesPastAnImagesKeypoints) {
  OwnTempDir dir;
  const Features a = sample_features("graf", 1), b = sample_features("graf", 2);
  Features few_b = b;
  few_b.keypoints.resize(100);
  few_b.descriptors.resize(100);
  {
    io::Hdf5File features(dir.file("f.h5"), io::Hdf5File::Mode::read_write);
    features.write_features("a.png", a);
    features.write_features("b.png", few_b);
    io::Hdf5File matches(dir.file("m.h5"), io::Hdf5File::Mode::read_write);
    matches.write_matches("a.png", "b.png", static_cast<int>(a.keypoints.size()),
                          match_descriptors(a.descriptors, b.descriptors));
  }
  std::ofstream(dir.file("pairs.txt")) << "a.png a.png\na.png b.png\n";
  try {
    io::export_colmap_database(dir.file("db.db"), dir.file("f.h5"), dir.file("m.h5"),
                               dir.file("pairs.txt"));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("pair 'a.png b.png': a match names keypoint "), std::string::npos)
        << message;
    EXPECT_NE(message.find("of 'b.png', which has 100 in"), std::string::npos) << message;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("db.db")));
  std::ofstream(dir.file("self.txt")) << "a.png a.png\n";
  const io::ColmapExport done = io::export_colmap_database(dir.file("db.db"), dir.file("f.h5"),
                                                           dir.file("m.h5"), dir.file("self.txt"));
  EXPECT_EQ(done.pairs, 0);
  ASSERT_EQ(done.notes.size(), 1u);
  EXPECT_NE(done.notes[0].find("paired with itself"), std::string::npos);
}
#endif

}  // namespace
}  // namespace aief

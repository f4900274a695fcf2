// Merging HDF5 feature files (shards of one collection, io/hdf5_merge.hpp): a failed merge leaves
// the output as it was, a rerun replaces what changed, the newer group is kept, an image is
// refused twice; python/tests/ reads the merged files back with h5py.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/feature_formats.hpp"
#include "tests/io_test_support.hpp"
#include "tests/test_support.hpp"

#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/hdf5_merge.hpp"

namespace aief {
namespace {

using OwnTempDir = test::TempFolder;  // a folder of this test's own, removed at the end
using test::expect_same;
using test::sample_features;
using test::temporaries_in;

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

// An image of an older file of its name than the output holds (another image of the same name, or
// an older shard) is refused naming both, as an image in two of the files merged is (before: kept
// with a note, "an older file of the image (an older shard?)", exit 0); a matches file is no shard
// (before: an empty output, exit 0).
TEST(Hdf5Features, MergeRefusesAnOlderImageOfTheSameNameAndAMatchesFile) {
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
  ASSERT_EQ(io::merge_feature_files(dir.file("all.h5"), {dir.file("new.h5")}, &replaced, &notes),
            1);
  try {
    io::merge_feature_files(dir.file("all.h5"), {dir.file("old.h5")}, &replaced, &notes);
    ADD_FAILURE() << "an older image of the same name merged";
  } catch (const Error& e) {
    const std::string said = e.what();
    EXPECT_NE(said.find("image 'a.png' of '" + dir.file("old.h5") + "' is of another file than "),
              std::string::npos)
        << said;
    EXPECT_NE(said.find("'" + dir.file("all.h5") + "' holds"), std::string::npos) << said;
    EXPECT_NE(said.find("nothing was written"), std::string::npos) << said;
  }
  EXPECT_TRUE(notes.empty());
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

// An output that is a symbolic link is written through: the link kept, its target holding the
// merge (before: the link replaced by a new file, its target left with the old images).
TEST(Hdf5Features, MergeOntoALinkWritesItsTarget) {
  OwnTempDir dir;
  const ExtractorOptions options;
  io::Hdf5File(dir.file("a.h5"), io::Hdf5File::Mode::read_write)
      .write_features("a.png", sample_features("boat", 1), nullptr, &options);
  io::Hdf5File(dir.file("b.h5"), io::Hdf5File::Mode::read_write)
      .write_features("b.png", sample_features("graf", 1), nullptr, &options);
  ASSERT_EQ(io::merge_feature_files(dir.file("real.h5"), {dir.file("a.h5")}), 1);
  std::filesystem::create_symlink("real.h5", dir.file("link.h5"));
  ASSERT_EQ(io::merge_feature_files(dir.file("link.h5"), {dir.file("b.h5")}), 1);
  EXPECT_TRUE(std::filesystem::is_symlink(dir.file("link.h5")));
  EXPECT_EQ(io::Hdf5File(dir.file("real.h5"), io::Hdf5File::Mode::read).feature_names(),
            (std::vector<std::string>{"a.png", "b.png"}));
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

}  // namespace
}  // namespace aief
#endif

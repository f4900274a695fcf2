// The npz writer and the pairs files (hloc's pairs lists) at the C++ level, so the sanitizer
// builds run them; python/tests/ reads the npz files back with numpy.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/npz_writer.hpp"
#include "io/pairs_file.hpp"
#include "tests/io_test_support.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

// A folder of this test's own, removed at the end.
using OwnTempDir = test::TempFolder;
using test::sample_features;

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

}  // namespace
}  // namespace aief

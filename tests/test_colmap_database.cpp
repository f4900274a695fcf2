// The COLMAP database export (io/colmap_database.hpp) from HDF5 features, matches and a pairs
// file at the C++ level, so the sanitizer builds run it; python/tests/ reads the database back
// with sqlite3 and colmap.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "tests/io_test_support.hpp"
#include "tests/test_support.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif
#ifdef AIEF_HAVE_COLMAP_EXPORT
#include "io/colmap_database.hpp"
#endif

namespace aief {
namespace {

// A folder of this test's own, removed at the end.
using OwnTempDir = test::TempFolder;
using test::sample_features;
using test::temporaries_in;

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

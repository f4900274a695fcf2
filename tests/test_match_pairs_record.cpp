// match --pairs records the matcher and the features it matched in each pair group
// (io/match_record.hpp), and a rerun keeps a pair only when both are as now: re-extracted
// features, a changed image or another --matcher make it match the pair again. Before, the rerun
// said "1 already in" and kept the stale matches (COLMAP then got 8 RANSAC inliers against 163
// for a fresh match).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/hdf5_file.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

test::CommandRun run(const std::string& arguments) {
  return test::run_shell(std::string(AIEF_CLI_PATH) + " " + arguments);
}

class MatchPairsRecord : public ::testing::Test {
 protected:
  MatchPairsRecord() : folder_("aief_match_pairs_record") {
    std::filesystem::create_directories(images());
    std::filesystem::copy_file(test::sample_path("graf", "img1.png"), images() + "/a.png");
    std::filesystem::copy_file(test::sample_path("graf", "img2.png"), images() + "/b.png");
    std::filesystem::copy_file(test::sample_path("boat", "img1.png"), images() + "/c.png");
    std::ofstream(pairs()) << "a.png b.png\nb.png c.png\n";
  }
  std::string images() const { return folder_.file("images"); }
  std::string pairs() const { return folder_.file("pairs.txt"); }
  std::string features() const { return folder_.file("f.h5"); }

  void extract(const std::string& flags) {
    const test::CommandRun r =
        run("extract --batch " + images() + " --format h5 -o " + features() + " " + flags);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  test::CommandRun match(const std::string& output, const std::string& flags = "") {
    return run("match --pairs " + pairs() + " --features-file " + features() + " -o " + output +
               " " + flags);
  }
  // Both pairs of `output` hold what a fresh match into a new file gives.
  void expect_fresh(const std::string& output, const std::string& flags) {
    const std::string fresh = folder_.file("fresh.h5");
    std::filesystem::remove(fresh);
    ASSERT_EQ(match(fresh, flags).status, 0);
    const io::Hdf5File kept(output, io::Hdf5File::Mode::read),
        made(fresh, io::Hdf5File::Mode::read);
    for (const auto& [name0, name1] : {std::pair{"a.png", "b.png"}, std::pair{"b.png", "c.png"}}) {
      const std::vector<Match> x = kept.read_matches(name0, name1),
                               y = made.read_matches(name0, name1);
      ASSERT_EQ(x.size(), y.size()) << name0 << " " << name1;
      for (std::size_t i = 0; i < x.size(); ++i)
        EXPECT_TRUE(x[i].query == y[i].query && x[i].train == y[i].train &&
                    x[i].distance == y[i].distance);
    }
  }

  test::TempFolder folder_;
};

TEST_F(MatchPairsRecord, ARerunKeepsOnlyPairsMadeAsNow) {
  extract("--n-features 300");
  const std::string matches = folder_.file("m.h5");
  ASSERT_NE(match(matches).output.find("2 pairs matched (mutual)"), std::string::npos);
  const test::CommandRun again = match(matches);
  EXPECT_NE(again.output.find("0 pairs matched (mutual), 0 matches, 2 already in"),
            std::string::npos)
      << again.output;

  // Another matcher: both pairs again, saying why.
  const test::CommandRun ratio = match(matches, "--matcher ratio");
  EXPECT_EQ(ratio.status, 0) << ratio.output;
  EXPECT_NE(ratio.output.find("2 pairs matched (ratio)"), std::string::npos) << ratio.output;
  EXPECT_NE(ratio.output.find("2 pairs of " + matches +
                              " matched again, since they were matched otherwise (kind mutual -> "
                              "ratio)"),
            std::string::npos)
      << ratio.output;
  expect_fresh(matches, "--matcher ratio");

  // Features re-extracted with other options (extract's resume redoes every image).
  extract("--n-features 500");
  const test::CommandRun reextracted = match(matches, "--matcher ratio");
  EXPECT_NE(reextracted.output.find("2 pairs matched (ratio)"), std::string::npos)
      << reextracted.output;
  EXPECT_NE(reextracted.output.find("the features of 'a.png': n_features 300 -> 500"),
            std::string::npos)
      << reextracted.output;
  expect_fresh(matches, "--matcher ratio");

  // One image changed and re-extracted: only its pairs again.
  std::filesystem::copy_file(test::sample_path("boat", "img2.png"), images() + "/c.png",
                             std::filesystem::copy_options::overwrite_existing);
  extract("--n-features 500");
  const test::CommandRun changed = match(matches, "--matcher ratio");
  EXPECT_NE(changed.output.find("1 pairs matched (ratio)"), std::string::npos) << changed.output;
  EXPECT_NE(changed.output.find("1 already in"), std::string::npos) << changed.output;
  EXPECT_NE(changed.output.find("the image of 'c.png' changed"), std::string::npos)
      << changed.output;
  expect_fresh(matches, "--matcher ratio");
}

TEST_F(MatchPairsRecord, APairGroupWithoutARecordIsMatchedAgain) {
  extract("--n-features 300");
  const std::string matches = folder_.file("m.h5");
  {  // as an older aief (or another tool) wrote it: no record, and matches that are not these
    io::Hdf5File file(matches, io::Hdf5File::Mode::read_write);
    file.write_matches("a.png", "b.png", 300, {{0, 0, 0}});
    file.close();
  }
  const test::CommandRun r = match(matches);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2 pairs matched"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no record of its matcher and features"), std::string::npos) << r.output;
  expect_fresh(matches, "");
}

#ifdef AIEF_HAVE_COLMAP_EXPORT
// colmap takes a pair's matches only when they were matched from the features the features file
// holds now (the pair group's record): before, features re-extracted with --mode orbslam2 (as many
// keypoints, so no index check caught it) gave a database of stale matches and exit 0.
TEST_F(MatchPairsRecord, ColmapRefusesMatchesOfFeaturesExtractedAgainNamingThePairs) {
  extract("--features 300");
  const std::string matches = folder_.file("m.h5");
  ASSERT_EQ(match(matches).status, 0);
  const test::CommandRun fresh = run("colmap --features " + features() + " --matches " + matches +
                                     " --pairs " + pairs() + " -o " + folder_.file("fresh.db"));
  EXPECT_EQ(fresh.status, 0) << fresh.output;

  extract("--features 300 --mode orbslam2");
  const std::string db = folder_.file("stale.db");
  const test::CommandRun stale = run("colmap --features " + features() + " --matches " + matches +
                                     " --pairs " + pairs() + " -o " + db);
  EXPECT_EQ(stale.status, 1) << stale.output;
  EXPECT_NE(stale.output.find("2 pair(s) of '" + matches + "' were matched from other features"),
            std::string::npos)
      << stale.output;
  EXPECT_NE(stale.output.find("(pair 'a.png b.png': the features of 'a.png': "), std::string::npos)
      << stale.output;
  EXPECT_NE(stale.output.find("'b.png c.png'"), std::string::npos) << stale.output;
  EXPECT_NE(stale.output.find("run aief match --pairs again"), std::string::npos) << stale.output;
  EXPECT_FALSE(std::filesystem::exists(db));

  // Matched again: taken.
  ASSERT_EQ(match(matches).status, 0);
  const test::CommandRun again = run("colmap --features " + features() + " --matches " + matches +
                                     " --pairs " + pairs() + " -o " + db);
  EXPECT_EQ(again.status, 0) << again.output;
}
#endif

}  // namespace
}  // namespace aief

// --matcher guided in the commands: match --pairs reads the keypoints it needs from the features
// file, match A B takes it as any matcher, and the commands that cannot run it say why.
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

class GuidedMatchCommand : public ::testing::Test {
 protected:
  GuidedMatchCommand() : folder_("aief_guided_match_command") {
    std::filesystem::create_directories(folder_.file("images"));
    for (const char* image : {"img1.png", "img2.png"})
      std::filesystem::copy_file(test::sample_path("boat", image),
                                 folder_.file("images") + "/" + image);
    std::ofstream(folder_.file("pairs.txt")) << "img1.png img2.png\n";
  }
  std::string features() const { return folder_.file("f.h5"); }
  std::size_t matched(const std::string& flags) {
    const std::string out = folder_.file("m.h5");
    std::filesystem::remove(out);
    const test::CommandRun r = run("match --pairs " + folder_.file("pairs.txt") +
                                   " --features-file " + features() + " -o " + out + " " + flags);
    EXPECT_EQ(r.status, 0) << r.output;
    return io::Hdf5File(out, io::Hdf5File::Mode::read).read_matches("img1.png", "img2.png").size();
  }
  test::TempFolder folder_;
};

TEST_F(GuidedMatchCommand, MatchPairsKeepsMoreThanItsSeeds) {
  const test::CommandRun extract = run("extract --batch " + folder_.file("images") +
                                       " --format h5 -o " + features() + " --n-features 2000");
  ASSERT_EQ(extract.status, 0) << extract.output;
  const std::size_t seeds = matched("--matcher mutual_ratio"), guided = matched("--matcher guided");
  EXPECT_GT(seeds, 100u);
  EXPECT_GT(guided, seeds + seeds / 10);  // the band brings back what the image's ratio dropped
  EXPECT_NE(matched("--matcher guided --epipolar-band 4"), guided);
}

TEST_F(GuidedMatchCommand, MatchAbTakesIt) {
  const test::CommandRun r = run("match " + test::sample_path("boat", "img1.png") + " " +
                                 test::sample_path("boat", "img2.png") + " --matcher guided");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("putative matches (guided)"), std::string::npos) << r.output;
}

TEST_F(GuidedMatchCommand, TheSweepRefusesIt) {
  const std::string a = test::sample_path("boat", "img1.png");
  const test::CommandRun r = run("adapt " + a + " " + a + " --matcher guided");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("matcher guided (two views of a 3D scene, by their epipolar geometry) "
                          "does not apply"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace aief

// aief extract --batch over the numbered frames of a video: the carried F takes them in natural
// order (a list as listed) and refuses shards; an .h5 output is one HDF5 file, which says when it
// holds images of no input.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;

// Frames as ffmpeg's frame_%d.png numbers them, cut from the bundled images.
fs::path numbered_frames(const fs::path& root, int count) {
  const fs::path video = root / "video";
  fs::create_directories(video);
  const cv::Mat image = aief::test::load_sample_gray("graf", "img1.png");
  for (int t = 0; t < count; ++t)
    cv::imwrite((video / ("frame_" + std::to_string(t) + ".png")).string(),
                image(cv::Rect(4 * t, 3 * t, 200, 160)));
  return video;
}

// The frames of a video with the carried F: before, frame_10.png came before frame_2.png (byte
// order), a list written in frame order was sorted the same way, and nothing said so (the order
// itself: BatchInputs.FramesKeepTheListsOrderAndAFoldersNaturalOrder).
TEST(Batch, CarriedTakesAFoldersFramesInNaturalOrderAndAListAsListedAndSaysSo) {
  const aief::test::TempFolder temp("aief_batch");
  const fs::path video = numbered_frames(temp.path(), 12);
  const aief::test::CommandRun folder = aief::test::run_command(
      AIEF_CLI_PATH, {"extract", "--batch", video.string(), "-o", (temp.path() / "a.h5").string(),
                      "--entropy-threshold", "carried", "--threads", "1", "--features", "200"});
  ASSERT_EQ(folder.status, 0) << folder.output;
  EXPECT_NE(folder.output.find("--entropy-threshold carried takes the frames of '" +
                               video.string() + "' in natural order of their names"),
            std::string::npos)
      << folder.output;
  const fs::path list = temp.path() / "frames.txt";
  {
    std::ofstream out(list);
    for (const int t : {3, 10, 2, 0, 1, 11, 4, 5, 6, 7, 8, 9})
      out << (video / ("frame_" + std::to_string(t) + ".png")).string() << "\n";
  }
  const aief::test::CommandRun listed = aief::test::run_command(
      AIEF_CLI_PATH, {"extract", "--batch", list.string(), "-o", (temp.path() / "b.h5").string(),
                      "--entropy-threshold", "carried", "--threads", "1", "--features", "200"});
  ASSERT_EQ(listed.status, 0) << listed.output;
  EXPECT_NE(listed.output.find("in the list's order"), std::string::npos) << listed.output;
  // Without carried, a batch stays sorted by name and says nothing of frames.
  const aief::test::CommandRun plain = aief::test::run_command(
      AIEF_CLI_PATH, {"extract", "--batch", list.string(), "-o", (temp.path() / "c.h5").string(),
                      "--threads", "1", "--features", "200"});
  ASSERT_EQ(plain.status, 0) << plain.output;
  EXPECT_EQ(plain.output.find("frames of"), std::string::npos) << plain.output;
}

TEST(Batch, CarriedRefusesShards) {
  // Before: shards of one video each carried their own F, and merged they differed from one
  // process (74 of 640 datasets) while docs/scale_out.md said byte-equal.
  const aief::test::TempFolder temp("aief_batch");
  const fs::path video = numbered_frames(temp.path(), 2);
  const aief::test::CommandRun r = aief::test::run_command(
      AIEF_CLI_PATH, {"extract", "--batch", video.string(), "-o", (temp.path() / "a.h5").string(),
                      "--entropy-threshold", "carried", "--shard", "0/2"});
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--entropy-threshold carried carries F from frame to frame"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(temp.path() / "a.h5"));
}

TEST(Batch, AnH5OutputWithoutFormatIsOneHdf5File) {
  // Before: `extract --batch DIR -o d.h5` made a folder d.h5 of JSON files.
  const aief::test::TempFolder temp("aief_batch");
  const fs::path video = numbered_frames(temp.path(), 2), h5 = temp.path() / "d.h5";
  const aief::test::CommandRun r = aief::test::run_command(
      AIEF_CLI_PATH, {"extract", "--batch", video.string(), "-o", h5.string()});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_regular_file(h5));
#ifdef AIEF_HAVE_HDF5
  EXPECT_EQ(aief::io::Hdf5File(h5.string(), aief::io::Hdf5File::Mode::read).feature_names().size(),
            2u);
#endif
}

#ifdef AIEF_HAVE_HDF5
TEST(Batch, AnH5HoldingImagesOfNoInputSaysSo) {
  // Before: a deleted image's group stayed in the shard (and in the merged file) without a word.
  const aief::test::TempFolder temp("aief_batch");
  const fs::path video = numbered_frames(temp.path(), 3), h5 = temp.path() / "f.h5";
  const std::vector<std::string> args = {"extract",   "--batch",    video.string(), "-o",
                                         h5.string(), "--features", "200"};
  ASSERT_EQ(aief::test::run_command(AIEF_CLI_PATH, args).status, 0);
  fs::remove(video / "frame_1.png");
  const aief::test::CommandRun again = aief::test::run_command(AIEF_CLI_PATH, args);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("holds 1 image(s) that are none of this run's inputs (deleted or "
                              "moved since an earlier run wrote them? the first: 'frame_1.png')"),
            std::string::npos)
      << again.output;
  EXPECT_EQ(aief::io::Hdf5File(h5.string(), aief::io::Hdf5File::Mode::read).feature_names().size(),
            3u);
}
#endif

}  // namespace

// aief extract --batch: one output per input whatever the names (colliding spellings, symlinks,
// '..', '%', names whose HDF5 groups would nest), an output never another output's folder
// (resuming: tests/test_batch_resume.cpp).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif
#include "tests/batch_run.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace aief::test::batch;  // fs, start, wait_for, run_batch, files_below, ...

TEST(Batch, CollidingSpellingsGetOneOutputEach) {
  // Names the old scheme (extension dropped, '/' -> "__", leading '.' and '_' stripped) mapped
  // onto five outputs for twelve inputs, and called the missing ones "already done".
  const aief::test::TempFolder temp("aief_batch");
  const fs::path images = temp.path() / "images", out = temp.path() / "out";
  const std::vector<std::string> names = {"a.png",      "a.jpg",     "a.PNG",      "sub/x.png",
                                          "sub__x.png", "_c.png",    "c.png",      ".c.png",
                                          "__c.png",    "d/e/f.png", "d__e/f.png", "d/e__f.png"};
  const char* const sources[] = {"graf", "boat", "leuven"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    fs::create_directories((images / names[i]).parent_path());
    const cv::Mat image = aief::test::load_sample_gray(sources[i % 3], "img1.png");
    ASSERT_TRUE(cv::imwrite((images / names[i]).string(),
                            image(cv::Rect(0, 0, 300 + 10 * static_cast<int>(i), 200))));
  }
  std::string report;
  const std::vector<std::string> args = {
      "extract", "--batch", images.string(), "-o", out.string(), "--features", "100"};
  ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
  EXPECT_NE(report.find("12 extracted, 0 already done"), std::string::npos) << report;
  EXPECT_EQ(files_below(out, ".json").size(), names.size());
  for (const std::string& name : names)
    expect_output_of(out / (name + ".json"), name, images / name);
  ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
  EXPECT_NE(report.find("0 extracted, 12 already done"), std::string::npos) << report;
}

TEST(Batch, AnOutputFileThatWouldBeAnotherOutputsFolderIsRefusedBeforeAnyWork) {
  const aief::test::TempFolder temp("aief_batch");
  const fs::path images = temp.path() / "images", out = temp.path() / "out";
  fs::create_directories(images / "a.png.json");
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "a.png");
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "a.png.json" / "b.png");
  const fs::path log = temp.path() / "stderr.log";
  const std::string command = std::string(AIEF_CLI_PATH) + " extract --batch " + images.string() +
                              " -o " + out.string() + " 2> " + log.string();
  EXPECT_EQ(WEXITSTATUS(std::system(command.c_str())), 1);
  EXPECT_NE(text_of(log).find("which is another input's output file"), std::string::npos)
      << text_of(log);
  EXPECT_TRUE(files_below(out, ".json").empty());
}

TEST(Batch, SymlinksAreNamedAsListedNeverResolved) {
  // A symlink farm: links to files elsewhere, two links to one file, a linked folder, a link
  // back to the root (a cycle, not followed) and a broken link (reported).
  const aief::test::TempFolder temp("aief_batch");
  const fs::path store = temp.path() / "store", farm = temp.path() / "farm",
                 out = temp.path() / "out";
  fs::create_directories(store / "deep");
  fs::create_directories(farm / "sub");
  const char* const sources[] = {"graf", "boat", "leuven"};
  for (int i = 0; i < 6; ++i) {
    const cv::Mat image = aief::test::load_sample_gray(sources[i % 3], "img2.png");
    const std::string number = std::to_string(i);
    cv::imwrite((store / ("s" + number + ".png")).string(),
                image(cv::Rect(0, 0, 320 + 8 * i, 240)));
    fs::create_symlink(store / ("s" + number + ".png"), farm / ("frame_" + number + ".png"));
  }
  fs::copy_file(store / "s0.png", store / "deep" / "s0.png");
  fs::create_symlink(store / "s1.png", farm / "sub" / "twin_a.png");
  fs::create_symlink(store / "s1.png", farm / "sub" / "twin_b.png");
  fs::create_directory_symlink(store / "deep", farm / "linked");
  fs::create_directory_symlink(farm, farm / "sub" / "loop");
  fs::create_symlink(store / "gone.png", farm / "broken.png");

  std::string report;
  EXPECT_EQ(
      run_batch({"extract", "--batch", farm.string(), "-o", out.string(), "--features", "100"},
                temp.path(), &report),
      1)
      << report;
  EXPECT_NE(report.find("9 extracted, 0 already done, 1 failed"), std::string::npos) << report;
  EXPECT_NE(report.find("broken.png"), std::string::npos) << report;
  const std::set<std::string> expected = {
      "frame_0.png.json",    "frame_1.png.json",    "frame_2.png.json",
      "frame_3.png.json",    "frame_4.png.json",    "frame_5.png.json",
      "sub/twin_a.png.json", "sub/twin_b.png.json", "linked/s0.png.json"};
  EXPECT_EQ(files_below(out, ".json"), expected);
  expect_output_of(out / "sub/twin_b.png.json", "sub/twin_b.png", farm / "sub" / "twin_b.png");
  expect_output_of(out / "linked/s0.png.json", "linked/s0.png", farm / "linked" / "s0.png");
}

TEST(Batch, ListNamesWithDotsAbsolutePathsAndPercentStayDistinctInsideTheOutputFolder) {
  const aief::test::TempFolder temp("aief_batch");
  const fs::path images = temp.path() / "work" / "images", out = temp.path() / "work" / "out";
  fs::create_directories(images / "%2E%2E");
  for (const char* name : {"a.png", "%2E%2E/a.png", "%25.png", "%.png"})
    fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / name);
  // Lines relative to the working folder and absolute ones; "./x" and "x" are one input.
  const fs::path list = temp.path() / "work" / "list.txt";
  std::ofstream(list)
      << "images/a.png\n./images/a.png\nimages/%2E%2E/a.png\nimages/%25.png\nimages/%.png\n"
      << (images / "a.png").string() << "\nimages/../images/a.png\n";
  std::string report;
  const fs::path previous = fs::current_path();
  fs::current_path(temp.path() / "work");
  const int status =
      run_batch({"extract", "--batch", list.string(), "-o", out.string(), "--features", "100"},
                temp.path(), &report);
  fs::current_path(previous);
  ASSERT_EQ(status, 0) << report;
  EXPECT_NE(report.find("6 extracted"), std::string::npos) << report;
  const std::string absolute =
      (fs::path("%2F") / images.relative_path() / "a.png.json").generic_string();
  const std::set<std::string> expected = {"images/a.png.json",
                                          "images/%252E%252E/a.png.json",
                                          "images/%2525.png.json",
                                          "images/%25.png.json",
                                          absolute,
                                          "images/%2E%2E/images/a.png.json"};
  EXPECT_EQ(files_below(out, ".json"), expected);
  for (const auto& entry : fs::recursive_directory_iterator(temp.path())) {
    if (entry.path().extension() == ".json") {
      EXPECT_EQ(entry.path().string().rfind(out.string(), 0), 0u) << entry.path();
    }
  }
}

#ifdef AIEF_HAVE_HDF5
TEST(Batch, NamesWhoseGroupsWouldNestInOneH5AreRefused) {
  // Before: `a` and `a/x.png` were both accepted, one group nested in the other (and writing `a`
  // after `a/x.png` replaced the group holding it).
  const aief::test::TempFolder temp("aief_batch");
  const fs::path d = temp.path() / "d", h5 = temp.path() / "f.h5", list = temp.path() / "l.txt";
  fs::create_directories(d);
  fs::copy_file(aief::test::sample_path("graf", "img1.png"), d / "a");
  std::ofstream(list) << "d/a\nd/a/x.png\n";
  const std::string cwd = "cd " + temp.path().string() + " && ";
  const aief::test::CommandRun both = aief::test::run_shell(
      cwd + AIEF_CLI_PATH + " extract --batch l.txt -o f.h5 --format h5 --features 200 2>&1");
  EXPECT_EQ(both.status, 1) << both.output;
  EXPECT_NE(both.output.find("would have its group inside the group of input 'd/a'"),
            std::string::npos)
      << both.output;
  EXPECT_FALSE(fs::exists(h5));
  // Across runs: the second name fails alone, the batch goes on and the file keeps the first.
  std::ofstream(list) << "d/a\n";
  ASSERT_EQ(aief::test::run_shell(cwd + AIEF_CLI_PATH +
                                  " extract --batch l.txt -o f.h5 --format h5 --features 200")
                .status,
            0);
  fs::remove(d / "a");
  fs::create_directories(d / "a");
  fs::copy_file(aief::test::sample_path("graf", "img2.png"), d / "a" / "x.png");
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), d / "b.png");
  std::ofstream(list) << "d/a/x.png\nd/b.png\n";
  const aief::test::CommandRun second = aief::test::run_shell(
      cwd + AIEF_CLI_PATH + " extract --batch l.txt -o f.h5 --format h5 --features 200 2>&1");
  EXPECT_EQ(second.status, 1) << second.output;
  EXPECT_NE(second.output.find("1 extracted, 0 already done, 1 failed"), std::string::npos)
      << second.output;
  EXPECT_NE(second.output.find("inside the group of image 'd/a'"), std::string::npos)
      << second.output;
  const std::vector<std::string> names =
      aief::io::Hdf5File(h5.string(), aief::io::Hdf5File::Mode::read).feature_names();
  EXPECT_EQ(names, (std::vector<std::string>{"d/a", "d/b.png"}));
}
#endif

}  // namespace

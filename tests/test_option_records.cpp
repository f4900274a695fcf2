// Every output records the options it was extracted with (io/option_record.hpp): a batch resume
// redoes an output of other options (saying which), keeps one whose options differ only where the
// output does not depend on them (threads), redoes an output without a record (an older aief's),
// and merge refuses shards of other options, naming both and the fields, before writing.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/feature_formats.hpp"
#include "io/option_record.hpp"
#include "io/source_record.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using aief::test::run_command;

// 'path', as messages name files.
std::string quoted(const fs::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

bool says(const aief::test::CommandRun& run, const std::string& text) {
  return run.output.find(text) != std::string::npos;
}

// The keypoints a batch reports ("...; 6000 keypoints").
long long keypoints_reported(const aief::test::CommandRun& run) {
  std::smatch found;
  if (!std::regex_search(run.output, found, std::regex("; ([0-9]+) keypoints"))) return -1;
  return std::stoll(found[1]);
}

// Two images to extract, in a folder of their own.
struct TwoImages {
  aief::test::TempFolder temp{"aief_records"};
  fs::path images = temp.path() / "images";
  TwoImages() {
    fs::create_directories(images);
    fs::copy_file(aief::test::sample_path("graf", "img1.png"), images / "a.png");
    fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "b.png");
  }
  std::vector<std::string> batch(const fs::path& output, const std::string& format,
                                 std::vector<std::string> options) const {
    std::vector<std::string> arguments = {"extract",       "--batch",  images.string(), "-o",
                                          output.string(), "--format", format};
    arguments.insert(arguments.end(), options.begin(), options.end());
    return arguments;
  }
};

std::vector<std::string> formats() {
  std::vector<std::string> all = {"json", "yml", "npz"};
#ifdef AIEF_HAVE_HDF5
  all.push_back("h5");
#endif
  return all;
}

TEST(OptionRecords, ResumeRedoesOutputsOfOtherOptionsInEveryFormat) {
  const TwoImages two;
  for (const std::string& format : formats()) {
    SCOPED_TRACE(format);
    const fs::path output = two.temp.path() / (format == "h5" ? "features.h5" : "out_" + format);
    const auto few = two.batch(output, format, {"--features", "500"});
    const auto many = two.batch(output, format, {"--features", "3000", "--mode", "orbslam2"});
    auto run = run_command(AIEF_CLI_PATH, few);
    ASSERT_EQ(run.status, 0) << run.output;
    ASSERT_TRUE(says(run, "2 extracted, 0 already done")) << run.output;
    // The thread count changes no byte of the output: kept.
    auto same = few;
    same.insert(same.end(), {"--threads", "1"});
    run = run_command(AIEF_CLI_PATH, same);
    EXPECT_TRUE(says(run, "0 extracted, 2 already done")) << run.output;

    run = run_command(AIEF_CLI_PATH, many);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_TRUE(says(run, "2 extracted (2 redone: n_features 500 -> 3000, ")) << run.output;
    EXPECT_TRUE(says(run, "distribution proportional -> quadtree")) << run.output;
    EXPECT_TRUE(says(run, ", 0 already done")) << run.output;
    EXPECT_GT(keypoints_reported(run), 2 * 500) << run.output;
    // The outputs now record the new options.
    run = run_command(AIEF_CLI_PATH, many);
    EXPECT_TRUE(says(run, "0 extracted, 2 already done")) << run.output;
  }
}

// The record of every file-per-image format reads back as the options written.
TEST(OptionRecords, EveryFormatReadsBackItsRecord) {
  const TwoImages two;
  aief::ExtractorOptions options;
  options.n_features = 700;
  aief::Features features;
  features.image_width = 8;
  features.image_height = 8;
  for (const char* extension : {".json", ".yml", ".npz"}) {
    SCOPED_TRACE(extension);
    const std::string path = two.temp.file(std::string("f") + extension);
    const aief::io::SourceRecord source{"x.png", 1, 2, {}};
    aief::io::write_features(path, "x.png", features, options, source);
    ASSERT_TRUE(aief::io::features_file_record(path, source).of_source);
    const auto record = aief::io::features_file_record(path, source).options;
    ASSERT_TRUE(record.has_value());
    EXPECT_TRUE(aief::io::option_changes(record, options).empty());
    aief::ExtractorOptions other = options;
    other.n_features = 800;
    other.threads = 3;
    EXPECT_EQ(aief::io::option_changes(record, other),
              std::vector<std::string>{"n_features 700 -> 800"});
  }
}

// An output written before outputs recorded their options: nothing says how it was made, so it
// is redone.
TEST(OptionRecords, AnOutputWithoutARecordIsRedone) {
  const TwoImages two;
  const fs::path out = two.temp.path() / "out";
  const auto args = two.batch(out, "json", {"--features", "500"});
  ASSERT_EQ(run_command(AIEF_CLI_PATH, args).status, 0);
  const fs::path json = out / "a.png.json";
  std::ifstream in(json);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::size_t begin = text.find("\"options\":"), end = text.find("},", begin);
  ASSERT_NE(end, std::string::npos);
  text.erase(begin, end + 2 - begin);
  std::ofstream(json, std::ios::trunc) << text;
  const auto run = run_command(AIEF_CLI_PATH, args);
  EXPECT_TRUE(says(run,
                   "1 extracted (1 redone: no option record (an older aief's output)), 1 "
                   "already done"))
      << run.output;
  EXPECT_TRUE(
      aief::io::features_file_record(
          json.string(), aief::io::source_record_of((two.images / "a.png").string(), "a.png"))
          .options.has_value());
}

#ifdef AIEF_HAVE_HDF5
TEST(OptionRecords, AnH5GroupWithoutARecordIsRedone) {
  const TwoImages two;
  const fs::path h5 = two.temp.path() / "features.h5";
  const auto args = two.batch(h5, "h5", {"--features", "500"});
  ASSERT_EQ(run_command(AIEF_CLI_PATH, args).status, 0);
  {
    aief::io::Hdf5File file(h5.string(), aief::io::Hdf5File::Mode::read_write);
    const aief::io::SourceRecord source =
        aief::io::source_record_of((two.images / "a.png").string(), "a.png");
    file.write_features("a.png", file.read_features("a.png"), &source);  // no options
    ASSERT_FALSE(file.option_record("a.png").has_value());
  }
  const auto run = run_command(AIEF_CLI_PATH, args);
  EXPECT_TRUE(says(run, "1 extracted (1 redone: no option record")) << run.output;
  EXPECT_TRUE(aief::io::Hdf5File(h5.string(), aief::io::Hdf5File::Mode::read)
                  .option_record("a.png")
                  .has_value());
}

TEST(OptionRecords, MergeRefusesShardsOfOtherOptionsNamingThemBeforeWriting) {
  const TwoImages two;
  const fs::path s0 = two.temp.path() / "s0.h5", s1 = two.temp.path() / "s1.h5",
                 merged = two.temp.path() / "features.h5";
  ASSERT_EQ(run_command(AIEF_CLI_PATH, two.batch(s0, "h5", {"--features", "500", "--shard", "0/2"}))
                .status,
            0);
  ASSERT_EQ(
      run_command(AIEF_CLI_PATH, two.batch(s1, "h5", {"--features", "1000", "--shard", "1/2"}))
          .status,
      0);
  auto run = run_command(AIEF_CLI_PATH, {"merge", "-o", merged.string(), s0.string(), s1.string()});
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_TRUE(says(run, "the options differ between " + quoted(s0) + " (image 'a.png') and " +
                            quoted(s1) + " (image 'b.png'): n_features 500 -> 1000;"))
      << run.output;
  EXPECT_TRUE(says(run, "nothing was written")) << run.output;
  EXPECT_FALSE(fs::exists(merged));

  // The same options (the thread count aside): merged.
  ASSERT_EQ(
      run_command(AIEF_CLI_PATH,
                  two.batch(s1, "h5", {"--features", "500", "--shard", "1/2", "--threads", "1"}))
          .status,
      0);
  run = run_command(AIEF_CLI_PATH, {"merge", "-o", merged.string(), s0.string(), s1.string()});
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(says(run, "2 images merged")) << run.output;

  // A shard of an aief that recorded no options, against the images already merged.
  const fs::path older = two.temp.path() / "older.h5";
  aief::io::Hdf5File(older.string(), aief::io::Hdf5File::Mode::read_write)
      .write_features("c.png", aief::io::Hdf5File(merged.string(), aief::io::Hdf5File::Mode::read)
                                   .read_features("a.png"));
  const auto size = fs::file_size(merged);
  run = run_command(AIEF_CLI_PATH, {"merge", "-o", merged.string(), older.string()});
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_TRUE(says(run, quoted(older) + " (image 'c.png') records no options")) << run.output;
  EXPECT_EQ(fs::file_size(merged), size);
}
#endif

}  // namespace

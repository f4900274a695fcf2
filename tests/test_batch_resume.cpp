// aief extract --batch resumed: after kill -9 (no half-written output, nothing redone, stale
// temporaries removed, an output of another input redone), two runs of one batch at once, every
// output format and one HDF5 file; shards split a collection exactly (the names of the outputs:
// tests/test_batch_names.cpp).
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/feature_formats.hpp"
#include "io/temporary_files.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif
#include "tests/batch_run.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace aief::test::batch;  // fs, start, wait_for, run_batch, files_below, ...

struct BatchFolder {
  aief::test::TempFolder temp{"aief_batch"};
  fs::path root = temp.path();
  fs::path images = root / "images", out = root / "out";
  int count = 0;
  BatchFolder() {
    fs::create_directories(images / "nested");
    // The bundled images under several names: enough work to kill the run halfway.
    for (int copy = 0; copy < 4; ++copy)
      for (const char* sequence : {"graf", "boat", "leuven"})
        for (const char* file : {"img1.png", "img2.png"}) {
          const fs::path target = (copy % 2 ? images / "nested" : images) /
                                  (std::string(sequence) + "_" + std::to_string(copy) + "_" + file);
          fs::copy_file(aief::test::sample_path(sequence, file), target);
          ++count;
        }
    std::ofstream(images / "broken.png") << "\x89PNG\r\n\x1a\n but then nothing";
  }
  std::set<std::string> outputs() const { return files_below(out, ".json"); }
};

TEST(Batch, ResumesAfterBeingKilledHalfway) {
  BatchFolder folder;
  const std::vector<std::string> args = {
      "extract", "--batch", folder.images.string(), "-o", folder.out.string(), "--threads", "1"};
  const pid_t pid = start(args);
  ASSERT_GT(pid, 0);
  for (int i = 0; i < 2000 && folder.outputs().size() < 3; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  wait_for(pid);
  const std::set<std::string> before = folder.outputs();
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), static_cast<std::size_t>(folder.count))
      << "the run finished before it could be killed";
  for (const std::string& name : before) {
    const std::string text = text_of(folder.out / name);
    EXPECT_EQ(text.rfind("]\n}\n"), text.size() - 4) << name << " is a half file";
  }
  std::map<std::string, fs::file_time_type> stamps;
  for (const std::string& name : before) stamps[name] = fs::last_write_time(folder.out / name);

  // The second run finishes the job, leaves the first run's outputs alone, reports the broken
  // image.
  EXPECT_EQ(run_batch(args, folder.root), 1) << "a failed image makes the exit status 1";
  const std::set<std::string> after = folder.outputs();
  EXPECT_EQ(after.size(), static_cast<std::size_t>(folder.count));
  for (const auto& [name, stamp] : stamps)
    EXPECT_EQ(fs::last_write_time(folder.out / name), stamp) << name << " was redone";
  for (const auto& entry : fs::recursive_directory_iterator(folder.images)) {
    if (!entry.is_regular_file() || entry.path().filename() == "broken.png") continue;
    const std::string name = entry.path().lexically_relative(folder.images).generic_string();
    expect_output_of(folder.out / (name + ".json"), name, entry.path());
  }
  EXPECT_TRUE(after.count("nested/graf_1_img1.png.json"));
  EXPECT_FALSE(after.count("broken.png.json"));
  EXPECT_TRUE(files_below(folder.out, ".tmp").empty());
}

// Two runs of one batch at once (a task resubmitted while the first still runs): each writes its
// own temporaries, so both end with exit 0 and every output is whole. Was: 16-28 false "failed"
// each, exit 1 (one shared temporary per output, taken or removed by the other run).
TEST(Batch, TwoRunsOfOneBatchAtOnceBothSucceed) {
  BatchFolder folder;
  fs::remove(folder.images / "broken.png");
  const std::vector<std::string> args = {
      "extract", "--batch", folder.images.string(), "-o", folder.out.string(), "--threads", "2"};
  for (int round = 0; round < 2; ++round) {  // the second round: redone (other options) at once
    std::vector<std::string> round_args = args;
    if (round == 1) round_args.insert(round_args.end(), {"--features", "700"});
    const fs::path log_a = folder.root / "a.log", log_b = folder.root / "b.log";
    const pid_t a = start(round_args, log_a), b = start(round_args, log_b);
    ASSERT_GT(a, 0);
    ASSERT_GT(b, 0);
    EXPECT_EQ(wait_for(a), 0) << text_of(log_a) << text_of(log_a.string() + ".err");
    EXPECT_EQ(wait_for(b), 0) << text_of(log_b) << text_of(log_b.string() + ".err");
    EXPECT_NE(text_of(log_a).find(" 0 failed"), std::string::npos) << text_of(log_a);
    EXPECT_NE(text_of(log_b).find(" 0 failed"), std::string::npos) << text_of(log_b);
  }
  EXPECT_EQ(folder.outputs().size(), static_cast<std::size_t>(folder.count));
  for (const auto& entry : fs::recursive_directory_iterator(folder.images)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().lexically_relative(folder.images).generic_string();
    expect_output_of(folder.out / (name + ".json"), name, entry.path());
  }
  EXPECT_TRUE(files_below(folder.out, ".tmp").empty());
}

TEST(Batch, ResumeRedoesOutputsOfOtherInputsAndRemovesStaleTemporaries) {
  const aief::test::TempFolder temp("aief_batch");
  const fs::path images = temp.path() / "images", out = temp.path() / "out";
  fs::create_directories(images / "sub");
  fs::copy_file(aief::test::sample_path("graf", "img1.png"), images / "changed.png");
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "kept.png");
  fs::copy_file(aief::test::sample_path("leuven", "img1.png"), images / "sub" / "cut.png");
  fs::copy_file(aief::test::sample_path("graf", "img2.png"), images / "planted.png");
  std::ofstream(images / "broken.png") << "not an image";
  const std::vector<std::string> args = {
      "extract", "--batch", images.string(), "-o", out.string(), "--features", "100"};
  std::string report;
  ASSERT_EQ(run_batch(args, temp.path(), &report), 1) << report;
  ASSERT_NE(report.find("4 extracted"), std::string::npos) << report;
  const fs::file_time_type kept_stamp = fs::last_write_time(out / "kept.png.json");

  // A new image under an old name; an output cut short; an output of another input copied in;
  // an output from another run beside a now broken input; temporaries a killed run left.
  fs::copy_file(aief::test::sample_path("leuven", "img2.png"), images / "changed.png",
                fs::copy_options::overwrite_existing);
  const std::string cut = text_of(out / "sub" / "cut.png.json");
  std::ofstream(out / "sub" / "cut.png.json") << cut.substr(0, cut.size() / 2);
  fs::copy_file(out / "kept.png.json", out / "planted.png.json",
                fs::copy_options::overwrite_existing);
  fs::copy_file(out / "kept.png.json", out / "broken.png.json");
  for (const char* stale : {"sub/cut.png.json", "broken.png.json", "kept.png.json"})
    std::ofstream(aief::io::temporary_path_of((out / stale).string())) << "half";
  std::ofstream(out / "kept.png.json.tmp") << "half";  // as an aief before the short names left it

  ASSERT_EQ(run_batch(args, temp.path(), &report), 1) << report;
  EXPECT_NE(report.find("3 extracted (3 replacing"), std::string::npos) << report;
  EXPECT_NE(report.find("1 already done, 1 failed"), std::string::npos) << report;
  EXPECT_EQ(fs::last_write_time(out / "kept.png.json"), kept_stamp);
  for (const char* name : {"changed.png", "kept.png", "sub/cut.png", "planted.png"})
    expect_output_of(out / (std::string(name) + ".json"), name, images / name);
  EXPECT_FALSE(fs::exists(out / "broken.png.json"))
      << "an output of another input beside a failure";
  EXPECT_TRUE(files_below(out, ".tmp").empty());
}

TEST(Batch, EveryFilePerImageFormatResumesOnlyItsOwnInput) {
  const aief::test::TempFolder temp("aief_batch");
  const fs::path images = temp.path() / "images";
  fs::create_directories(images / "sub");
  fs::copy_file(aief::test::sample_path("graf", "img1.png"), images / "sub" / "a.png");
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "sub__a.png");
  for (const char* format : {"json", "yml", "npz"}) {
    SCOPED_TRACE(format);
    const fs::path out = temp.path() / format;
    const std::vector<std::string> args = {"extract", "--batch",    images.string(),
                                           "-o",      out.string(), "--format",
                                           format,    "--features", "100"};
    std::string report;
    ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
    EXPECT_NE(report.find("2 extracted, 0 already done"), std::string::npos) << report;
    EXPECT_EQ(files_below(out, std::string(".") + format).size(), 2u);
    ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
    EXPECT_NE(report.find("0 extracted, 2 already done"), std::string::npos) << report;
    // The other image under the first one's name: its output no longer belongs, and is redone.
    fs::copy_file(aief::test::sample_path("leuven", "img1.png"), images / "sub" / "a.png",
                  fs::copy_options::overwrite_existing);
    ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
    EXPECT_NE(report.find("1 extracted (1 replacing"), std::string::npos) << report;
    const std::string output = (out / "sub" / (std::string("a.png.") + format)).string();
    EXPECT_TRUE(aief::io::features_file_belongs_to(
        output, aief::io::source_record_of((images / "sub" / "a.png").string(), "sub/a.png")));
    EXPECT_FALSE(aief::io::features_file_belongs_to(
        output, aief::io::source_record_of((images / "sub__a.png").string(), "sub/a.png")));
    fs::copy_file(aief::test::sample_path("graf", "img1.png"), images / "sub" / "a.png",
                  fs::copy_options::overwrite_existing);
  }
}

#ifdef AIEF_HAVE_HDF5
// One HDF5 file holds every image: a resume keeps the groups written from the files as they are,
// redoes a group whose file changed, and drops the group of a file that no longer reads.
TEST(Batch, H5ResumeRedoesTheGroupOfAChangedFileAndDropsTheGroupOfABrokenOne) {
  const aief::test::TempFolder temp("aief_batch");
  const fs::path images = temp.path() / "images", h5 = temp.path() / "features.h5";
  fs::create_directories(images);
  fs::copy_file(aief::test::sample_path("graf", "img1.png"), images / "changed.png");
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "kept.png");
  fs::copy_file(aief::test::sample_path("leuven", "img1.png"), images / "breaks.png");
  const std::vector<std::string> args = {"extract",  "--batch", images.string(), "-o", h5.string(),
                                         "--format", "h5",      "--features",    "100"};
  std::string report;
  ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
  ASSERT_NE(report.find("3 extracted, 0 already done"), std::string::npos) << report;
  ASSERT_EQ(run_batch(args, temp.path(), &report), 0) << report;
  EXPECT_NE(report.find("0 extracted, 3 already done"), std::string::npos) << report;

  fs::copy_file(aief::test::sample_path("leuven", "img2.png"), images / "changed.png",
                fs::copy_options::overwrite_existing);
  std::ofstream(images / "breaks.png", std::ios::trunc) << "not an image any more";
  ASSERT_EQ(run_batch(args, temp.path(), &report), 1) << report;
  EXPECT_NE(report.find("1 extracted (1 replacing"), std::string::npos) << report;
  EXPECT_NE(report.find("1 already done, 1 failed"), std::string::npos) << report;

  const aief::io::Hdf5File file(h5.string(), aief::io::Hdf5File::Mode::read);
  EXPECT_EQ(file.feature_names(), (std::vector<std::string>{"changed.png", "kept.png"}));
  for (const char* name : {"changed.png", "kept.png"})
    EXPECT_TRUE(
        file.features_belong_to(name, aief::io::source_record_of((images / name).string(), name)))
        << name;
  const cv::Mat changed = cv::imread((images / "changed.png").string(), cv::IMREAD_GRAYSCALE);
  const aief::Features features = file.read_features("changed.png");
  EXPECT_EQ(features.image_width, changed.cols);
  EXPECT_EQ(features.image_height, changed.rows);
}
#endif

TEST(Batch, ShardsSplitTheCollectionExactly) {
  BatchFolder folder;
  std::set<std::string> seen;
  std::size_t total = 0;
  for (int shard = 0; shard < 3; ++shard) {
    const fs::path out = folder.root / ("shard" + std::to_string(shard));
    run_batch({"extract", "--batch", folder.images.string(), "-o", out.string(), "--shard",
               std::to_string(shard) + "/3", "--features", "100"},
              folder.root);
    for (const std::string& name : files_below(out, ".json")) {
      seen.insert(name);
      ++total;
    }
  }
  EXPECT_EQ(total, static_cast<std::size_t>(folder.count)) << "an image in two shards, or in none";
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(folder.count));
}

}  // namespace

// aief extract --batch: one output per input whatever the names (colliding spellings, symlinks,
// '..', '%'), resumes after kill -9 (no half-written output, nothing redone, stale temporaries
// removed, an output of another input redone), skips a corrupt image with its reason, shards
// split a collection exactly.
#include <fcntl.h>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/feature_formats.hpp"
#include "io/json_writer.hpp"
#include "io/temporary_files.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif
#include "tests/test_support.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;

// The files below `folder` with `extension`, as paths relative to it.
std::set<std::string> files_below(const fs::path& folder, const std::string& extension) {
  std::set<std::string> names;
  if (fs::exists(folder))
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.is_regular_file() && entry.path().string().size() > extension.size() &&
          entry.path().string().compare(entry.path().string().size() - extension.size(),
                                        extension.size(), extension) == 0)
        names.insert(entry.path().lexically_relative(folder).generic_string());
  return names;
}

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

pid_t start(const std::vector<std::string>& arguments, const fs::path& log = "/dev/null") {
  std::vector<char*> argv;
  std::string binary = AIEF_CLI_PATH;
  argv.push_back(binary.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  // stderr beside the log (a sanitizer's report, a message), or nowhere when there is no log.
  const std::string errors = log == "/dev/null" ? log.string() : log.string() + ".err";
  posix_spawn_file_actions_addopen(&actions, 2, errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Runs a batch to the end; returns the exit status, and its stdout in `report`.
int run_batch(const std::vector<std::string>& arguments, const fs::path& scratch,
              std::string* report = nullptr) {
  const fs::path log = scratch / "batch.log";
  const int status = wait_for(start(arguments, log));
  if (report) *report = text_of(log);
  fs::remove(log);
  return status;
}

// The output parses (OpenCV's JSON reader), holds one descriptor per keypoint and records the
// input `name` read from `path`, with its current size and time.
void expect_output_of(const fs::path& output, const std::string& name, const fs::path& path) {
  SCOPED_TRACE(output.string());
  cv::FileStorage file(output.string(), cv::FileStorage::READ);
  ASSERT_TRUE(file.isOpened());
  EXPECT_EQ(static_cast<std::string>(file["source"]["name"]), name);
  EXPECT_EQ(static_cast<double>(file["source"]["bytes"]), static_cast<double>(fs::file_size(path)));
  EXPECT_GT(file["keypoints"].size(), 10u);
  EXPECT_EQ(file["keypoints"].size(), file["descriptors_hex"].size());
  EXPECT_TRUE(aief::io::features_file_belongs_to(output.string(),
                                                 aief::io::source_record_of(path.string(), name)));
}

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

namespace {

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
                      "--threshold", "carried", "--threads", "1", "--features", "200"});
  ASSERT_EQ(folder.status, 0) << folder.output;
  EXPECT_NE(folder.output.find("takes the frames of '" + video.string() +
                               "' in natural order of their names"),
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
                      "--threshold", "carried", "--threads", "1", "--features", "200"});
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
                      "--threshold", "carried", "--shard", "0/2"});
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--threshold carried carries F from frame to frame"), std::string::npos)
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

namespace {

#ifdef AIEF_HAVE_HDF5
TEST(Batch, AnH5HoldingImagesOfNoInputSaysSo) {
  // Before: a deleted image's group stayed in the shard (and in the merged file) without a word.
  const aief::test::TempFolder temp("aief_batch");
  const fs::path video = numbered_frames(temp.path(), 3), h5 = temp.path() / "f.h5";
  const std::vector<std::string> args = {"extract", "--batch", video.string(), "-o", h5.string(),
                                         "--features", "200"};
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

// The aief command line as a user meets it: help, every error path's message and exit status,
// and the files it writes.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_support.hpp"

namespace {

using CliResult = aief::test::CommandRun;  // status, and stdout + stderr

std::string aief_binary() { return std::string(AIEF_CLI_PATH); }

CliResult run(const std::string& arguments) {
  return aief::test::run_shell(aief_binary() + " " + arguments);
}

TEST(Cli, HelpAndVersion) {
  EXPECT_EQ(run("--help").status, 0);
  EXPECT_EQ(run("extract --help").status, 0);
  EXPECT_NE(run("extract --help").output.find("--threshold"), std::string::npos);
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("--version").status, 0);
  const CliResult kernels = run("--print-kernels");
  EXPECT_EQ(kernels.status, 0);
  EXPECT_NE(kernels.output.find("scalar"), std::string::npos);
}

// --print-kernels names every kernel and the code each set runs for it, and says what AIEF_KERNELS
// made the default; a value of AIEF_KERNELS that cannot apply is an error before any work.
TEST(Cli, KernelsListedAndForcedByTheEnvironment) {
  struct Environment {
    ~Environment() { unsetenv("AIEF_KERNELS"); }
  } restore;
  const CliResult listing = run("--print-kernels");
  ASSERT_EQ(listing.status, 0) << listing.output;
  for (const char* kernel : {"resize_bilinear_rows", "fast9_scores_row", "hamming_256_blocked",
                             "positions_within_bounds"})
    EXPECT_NE(listing.output.find(kernel), std::string::npos) << kernel << " missing from\n"
                                                              << listing.output;

  setenv("AIEF_KERNELS", "scalar", 1);
  const CliResult forced = run("--print-kernels");
  EXPECT_EQ(forced.status, 0);
  EXPECT_NE(forced.output.find("default: scalar (AIEF_KERNELS=scalar)"), std::string::npos)
      << forced.output;

  setenv("AIEF_KERNELS", "fastest", 1);
  const CliResult refused = run("extract " + aief::test::sample_path("graf", "img1.png"));
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.output.find("aief: error: AIEF_KERNELS=fastest: unknown kernel set"),
            std::string::npos)
      << refused.output;
}

TEST(Cli, UsageErrorsExitTwoAndNameTheProblem) {
  const std::string image = aief::test::sample_path("graf", "img1.png");
  const std::string second = aief::test::sample_path("graf", "img2.png");
  struct Case {
    std::string args, mention;
  };
  const Case cases[] = {
      {"frobnicate", "unknown command"},
      {"extract " + image + " --features abc", "--features"},
      {"extract " + image + " --features 0", "--features"},
      {"extract " + image + " --scale 0.8", "--scale"},
      {"extract " + image + " --levels 99", "--levels"},
      {"extract " + image + " --threshold nan", "--threshold"},
      {"extract " + image + " --mode orb", "unknown mode"},
      {"extract " + image + " --kernels neon", "unknown kernel set"},
      {"extract " + image + " --bogus", "unknown option --bogus"},
      {"extract", "one IMAGE"},
      {"extract " + image + " --features", "expects a value"},
      {"match " + image, "two images"},
      {"eval", "--dataset"},
      {"extract " + image + " --pool 0.5", "--pool expects a number >= 1, inf or off, got '0.5'"},
      {"extract " + image + " --pool many", "--pool expects"},
      {"extract " + image + " --coordinates centre", "unknown coordinate map"},
      {"extract " + image + " --subpixel yes", "--subpixel"},
      {"extract " + image + " --starvation-guard block", "unknown starvation guard"},
      {"extract " + image + " --auto-uniform-blocks maybe", "--auto-uniform-blocks"},
      {"extract " + image + " --ranking harris", "unknown candidate ranking"},
      {"extract " + image + " --auto-two-classes yes", "--auto-two-classes"},
      {"eval --dataset . --ranking harris", "unknown candidate ranking"},
      {"eval --dataset . --methods orb", "unknown method"},
      // eval's matcher flags are the match rows' (core/options/matching_option_rows.cpp), as in
      // match.
      {"eval --dataset . --matcher flann", "unknown matcher 'flann' for --matcher"},
      {"eval --dataset . --ratio 0.7",
       "--ratio applies to --matcher ratio, mutual_ratio or guided only"},
      // eval's extractor flags are the extractor rows' but those each row sets itself.
      {"eval --dataset . --quadtree-weight heavy", "--quadtree-weight"},
      {"eval --dataset . --threshold 3", "unknown option --threshold"},
      {"eval --dataset . --mode orbslam2", "unknown option --mode"},
      {"eval --dataset . --threads 2", "unknown option --threads"},
      {"eval --dataset . --entropy off", "--entropy off leaves aief_adaptive"},
      {"eval --dataset . --methods opencv_orb,orbslam2 --n-features 500",
       "--n-features sets the options of the aief mode's rows"},
      // Flags a mode cannot honour are refused with the conflict named, never dropped.
      {"extract " + image + " --mode orbslam2 --threshold 7",
       "--threshold sets F of the entropy mask, which --mode orbslam2"},
      {"extract " + image + " --mode orbslam2 --entropy intensity",
       "--mode orbslam2 means --entropy off, so --entropy intensity cannot apply"},
      {"extract " + image + " --entropy off --threshold 3", "which --entropy off turns off"},
      {"extract " + image + " --entropy off --threshold auto", "--threshold"},
      {"extract " + image + " --format yml", "--format applies to --batch only"},
      {"extract " + image + " --shard 0/2", "--shard applies to --batch only"},
      {"extract --batch x -o y --draw p.png", "--draw pictures one image"},
      {"match " + image + " " + second + " --epipolar-band 2",
       "--epipolar-band applies to --matcher guided only"},
      {"eval --dataset . --matcher guided", "--matcher guided matches two views of a 3D scene"},
      {"match " + image + " " + image + " --ratio 0.7",
       "--ratio applies to --matcher ratio, mutual_ratio or guided only"},
      // An unknown output format, before any work (no keypoint count printed).
      {"extract " + image + " -o out.txt", "must end in .json, .yml, .yaml or .npz"},
      // 1 is outside the range, and the message says so.
      {"extract " + image + " --scale 1.0", "--scale expects a number in (1, 4], got '1.0'"},
      // Shards count from 0; 1-based arrays get the recipe; no overflow.
      {"extract --batch x -o y --shard 4/4", "SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN"},
      {"extract --batch x -o y --shard 0/99999999999", "0 <= i < n <= 2147483647"},
      {"extract --batch x -o y --shard 0/4294967297", "0 <= i < n <= 2147483647"},
      {"extract --batch x -o y --shard -1/4", "--shard expects i/n"},
      {"extract --batch x -o y --shard 1/0", "--shard expects i/n"},
      {"extract --batch x -o y --shard 1/4x", "--shard expects i/n"},
      {"extract --batch x -o y --shard 1", "--shard expects i/n"},
      // Options that cannot act here are refused, not accepted for the same bytes.
      {"extract " + image + " --detection-cells orbslam --candidate-ranking peak",
       "--candidate-ranking"},
      {"extract " + image + " --entropy-threshold carried",
       "--entropy-threshold carried takes F from the frames of a video"},
      {"match " + image + " " + second + " --entropy-threshold carried",
       "match A B has no frame before its images"},
      // A JSON output under another format's name; the matches of --pairs are HDF5.
      {"match " + image + " " + second + " -o m.npz", "-o m.npz: this command writes JSON"},
      {"adapt " + image + " " + second + " -o a.yml", "so the file's name must end in .json"},
      {"match --pairs p.txt --features-file f.h5 -o m.json", "must end in .h5"},
      // The sweep's commands name the flag that leaves them no entropy.
      {"adapt " + image + " " + second + " --entropy off",
       "adapt sweeps the entropy threshold, "
       "and --entropy off measures no entropy"},
      {"match " + image + " " + second + " --adaptive --mode orbslam2",
       "--mode orbslam2 measures no entropy"},
      // A flag given twice, by one spelling or by two, is refused naming both: never the last.
      {"extract " + image + " --n-features 500 --n-features 800",
       "--n-features is given twice: give it once"},
      {"extract " + image + " --features 500 --n-features=800",
       "--features and --n-features are two spellings of one option, both given"},
      {"extract " + image + " -o a.json --output b.json",
       "-o and --output are two spellings of one option"},
      {"match " + image + " " + second + " --adaptive --adaptive", "--adaptive is given twice"},
      {"merge -o m.h5 --output n.h5 s.h5", "-o and --output are two spellings"},
      {"colmap --features f.h5 --features-file g.h5 --matches m.h5 -o c.db",
       "--features and --features-file are two spellings"},
      // A smoothing that runs another value's passes (the same bytes, another record).
      {"extract " + image + " --detection-smoothing 0.5",
       "detection_smoothing 0.5 runs 1 pass of the 5x5 binomial, as 1 does"},
      {"extract " + image + " --detection-smoothing 1e-320", "as 1 does"},
  };
  for (const Case& c : cases) {
    const CliResult r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find("aief: error:"), std::string::npos) << c.args;
    EXPECT_NE(r.output.find(c.mention), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find("keypoints"), std::string::npos)
        << c.args << " did work before refusing\n"
        << r.output;
  }
}

TEST(Cli, FlagsGivenOverrideTheModeAndTakeEffect) {
  const aief::test::TempFolder folder("aief_cli");
  const std::string image = aief::test::sample_path("boat", "img1.png");
  struct Case {
    std::string flags;
    std::vector<std::string> in_json;
  };
  const Case cases[] = {
      {"--entropy off", {"\"distribution\":\"proportional\"", "\"entropy\":\"off\""}},
      {"--mode orbslam2 --entropy off", {"\"distribution\":\"quadtree\"", "\"entropy\":\"off\""}},
      {"--mode quadtree-entropy --entropy intensity --threshold 7",
       {"\"distribution\":\"quadtree\"", "\"entropy\":\"intensity\"", "\"entropy_threshold\":7"}},
      {"--mode aief --entropy intensity --threshold auto",
       {"\"entropy\":\"intensity\"", "\"auto_threshold\":true"}},
  };
  for (const Case& c : cases) {
    const std::string output = folder.file("f.json");
    const CliResult r = run("extract " + image + " --features 200 " + c.flags + " -o " + output);
    ASSERT_EQ(r.status, 0) << c.flags << "\n" << r.output;
    std::ifstream in(output);
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const std::string& expected : c.in_json)
      EXPECT_NE(json.find(expected), std::string::npos) << c.flags << ": " << expected;
  }
  // More threads than the machine has: used as many as there are, said in aief's words.
  const CliResult many = run("extract " + image + " --features 200 --threads 256");
  EXPECT_EQ(many.status, 0) << many.output;
  EXPECT_EQ(many.output.find("TBB"), std::string::npos) << many.output;
  if (std::thread::hardware_concurrency() < 256) {
    EXPECT_NE(many.output.find("aief: note: --threads 256 is more than the"), std::string::npos)
        << many.output;
  }
}

// A ground truth that is no homography is refused before any work, naming the file and the fault.
TEST(Cli, EvalRefusesGroundTruthsThatAreNoHomography) {
  const aief::test::TempFolder folder("aief_cli");
  const std::filesystem::path sequence = folder.path() / "graf";
  std::filesystem::create_directories(sequence);
  for (const char* image : {"img1.png", "img2.png"})
    std::filesystem::copy_file(aief::test::sample_path("graf", image), sequence / image);
  struct Case {
    std::string numbers, mention;
  };
  const Case cases[] = {
      {"1 0 0 0 nan 0 0 0 1", "'nan' is not a finite number"},
      {"1 0 0 0 1 0 0 0 inf", "'inf' is not a finite number"},
      {"0 0 0 0 0 0 0 0 0", "is all zeros"},
      {"1 2 3 2 4 6 0 0 1", "is singular"},
      {"1 0 0 0 1 0 0 0 1 7", "holds more than 9 numbers"},
      {"1 0 0 0 1 0 0 0", "fewer than 9 numbers"},
      {"1 0 0 0 1 0 0 0 1x", "'1x' is not a number"},
  };
  for (const Case& c : cases) {
    std::ofstream(sequence / "H1to2p") << c.numbers << "\n";
    const CliResult r =
        run("eval --dataset " + folder.path().string() + " --pairs 1-2 --methods orbslam2 -o " +
            (folder.path() / "report.md").string());
    EXPECT_EQ(r.status, 1) << c.numbers << "\n" << r.output;
    EXPECT_NE(r.output.find(c.mention), std::string::npos) << c.numbers << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(folder.path() / "report.md")) << c.numbers;
  }
}

#ifdef AIEF_HAVE_HDF5
// hloc names a pair's group with '/' -> '-': "a/b.png c.png" and "a-b.png c.png" would share one.
// Refused before any work, naming both lines; a self-pair and a '#' line are skipped and said.
TEST(Cli, MatchPairsRefusesPairsSharingAGroupAndSaysWhatItSkips) {
  const aief::test::TempFolder folder("aief_cli");
  const std::filesystem::path images = folder.path() / "images";
  std::filesystem::create_directories(images / "a");
  std::filesystem::copy_file(aief::test::sample_path("boat", "img1.png"), images / "a" / "b.png");
  std::filesystem::copy_file(aief::test::sample_path("boat", "img2.png"), images / "a-b.png");
  std::filesystem::copy_file(aief::test::sample_path("graf", "img1.png"), images / "c.png");
  const std::string features = (folder.path() / "f.h5").string(),
                    matches = (folder.path() / "m.h5").string();
  ASSERT_EQ(run("extract --batch " + images.string() + " -o " + features +
                " --format h5 --n-features 300")
                .status,
            0);
  const std::string pairs = (folder.path() / "pairs.txt").string();
  std::ofstream(pairs) << "a/b.png c.png\na-b.png c.png\n";
  const CliResult collide =
      run("match --pairs " + pairs + " --features-file " + features + " -o " + matches);
  EXPECT_EQ(collide.status, 1) << collide.output;
  EXPECT_NE(collide.output.find(
                "line 2 ('a-b.png c.png') and line 1 ('a/b.png c.png') name one pair group"),
            std::string::npos)
      << collide.output;
  EXPECT_FALSE(std::filesystem::exists(matches));
  std::ofstream(pairs) << "#a.png c.png\nc.png c.png\na/b.png c.png\n";
  // The features file's earlier flag, --features (now --n-features' earlier spelling), still
  // names it with --pairs, with a note (CHANGELOG.md).
  const CliResult noted =
      run("match --pairs " + pairs + " --features " + features + " -o " + matches);
  EXPECT_EQ(noted.status, 0) << noted.output;
  EXPECT_NE(noted.output.find("--pairs' features file is --features-file now"), std::string::npos)
      << noted.output;
  EXPECT_NE(noted.output.find("line 1 skipped: it begins with '#'"), std::string::npos)
      << noted.output;
  EXPECT_NE(noted.output.find("line 2 skipped: 'c.png' paired with itself"), std::string::npos)
      << noted.output;
  EXPECT_NE(noted.output.find("1 pairs matched"), std::string::npos) << noted.output;
  // A later run asking the other pair of that group is refused, never given the first's matches.
  std::ofstream(pairs) << "a-b.png c.png\n";
  const CliResult later =
      run("match --pairs " + pairs + " --features-file " + features + " -o " + matches);
  EXPECT_EQ(later.status, 1) << later.output;
  EXPECT_NE(later.output.find("pair 'a-b.png c.png' and pair 'a/b.png c.png' share the group"),
            std::string::npos)
      << later.output;
}
#endif

TEST(Cli, InputErrorsExitOne) {
  const aief::test::TempFolder folder("aief_cli");
  const std::filesystem::path& dir = folder.path();
  std::ofstream((dir / "notes.png").string()) << "not an image";
  const CliResult missing = run("extract " + (dir / "missing.png").string());
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.output.find("missing.png"), std::string::npos);
  const CliResult text = run("extract " + (dir / "notes.png").string());
  EXPECT_EQ(text.status, 1);
  EXPECT_NE(text.output.find("notes.png"), std::string::npos);
  const CliResult bad_output = run("extract " + aief::test::sample_path("boat", "img1.png") +
                                   " -o " + (dir / "f.txt").string());
  EXPECT_EQ(bad_output.status, 2)
      << "an unknown output format is a usage error, found before any work";
  // validate on an image no extraction takes: refused, not "identical" untested.
  std::ofstream((dir / "tiny.pgm").string(), std::ios::binary) << "P5\n7 3\n255\n"
                                                               << std::string(21, '\x40');
  const CliResult tiny = run("validate " + (dir / "tiny.pgm").string());
  EXPECT_EQ(tiny.status, 1) << tiny.output;
  EXPECT_NE(tiny.output.find("cannot validate on '" + (dir / "tiny.pgm").string() +
                             "': image 7x3 is smaller than"),
            std::string::npos)
      << tiny.output;
  // validate on a uniform image: no keypoint, so the kernels of keypoints tested nothing while
  // every row said "identical".
  std::ofstream((dir / "flat.pgm").string(), std::ios::binary) << "P5\n64 64\n255\n"
                                                               << std::string(64 * 64, '\x80');
  const CliResult flat = run("validate " + (dir / "flat.pgm").string());
  EXPECT_EQ(flat.status, 1) << flat.output;
  EXPECT_NE(flat.output.find("no keypoint in it"), std::string::npos) << flat.output;
  EXPECT_EQ(flat.output.find("identical"), std::string::npos) << flat.output;
}

TEST(Cli, EveryCommandRefusesADecompressionBombBeforeDecoding) {
  // A valid PNG declaring 30000 x 30000: decoded, it would take 0.9 GB (RGB: 2.7 GB) before the
  // extractor's own size check. Each command must refuse it from the header.
  const aief::test::TempFolder folder("aief_cli");
  const std::filesystem::path& dir = folder.path();
  const std::vector<std::uint8_t> bomb = aief::test::png_declaring(30000, 30000);
  for (const char* path : {"bomb.png", "eval/graf/img1.png", "batch/bomb.png"}) {
    std::filesystem::create_directories((dir / path).parent_path());
    std::ofstream((dir / path).string(), std::ios::binary)
        .write(reinterpret_cast<const char*>(bomb.data()),
               static_cast<std::streamsize>(bomb.size()));
  }
  const std::string good = aief::test::sample_path("graf", "img2.png"),
                    bomb_path = (dir / "bomb.png").string();
  std::filesystem::copy_file(good, dir / "eval/graf/img2.png");
  std::filesystem::copy_file(aief::test::sample_path("graf", "H1to2p"), dir / "eval/graf/H1to2p");
  const std::string commands[] = {
      "extract " + bomb_path,
      "match " + bomb_path + " " + good,
      "adapt " + good + " " + bomb_path,
      "eval --dataset " + (dir / "eval").string() + " --sequences graf --pairs 1-2 -o " +
          (dir / "report.md").string(),
      "extract --batch " + (dir / "batch").string() + " -o " + (dir / "out").string(),
      "bench " + bomb_path,
      "bench " + good + " --pair " + bomb_path};
  for (const std::string& command : commands) {
    const CliResult r = run(command);
    EXPECT_EQ(r.status, 1) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("declares 30000x30000 pixels in its PNG header"), std::string::npos)
        << command << "\n"
        << r.output;
    EXPECT_NE(r.output.find("refused before decoding"), std::string::npos) << command << "\n"
                                                                           << r.output;
  }
  // bench reads as every command does, by the limit given (--max-image-pixels), not the default.
  const CliResult small_limit = run("bench " + good + " --max-image-pixels 1000 --repeat 1");
  EXPECT_EQ(small_limit.status, 1) << small_limit.output;
  EXPECT_NE(small_limit.output.find("more than max_image_pixels = 1000 (refused before decoding)"),
            std::string::npos)
      << small_limit.output;
}

TEST(Cli, AJpegCutShortIsExtractedWithTheDecodersWarning) {
  const aief::test::TempFolder folder("aief_cli");
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", cv::imread(aief::test::sample_path("boat", "img1.png")), bytes);
  bytes.resize(bytes.size() / 3);
  std::ofstream(folder.file("cut.jpg"), std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  const CliResult r = run("extract " + folder.file("cut.jpg") + " -o " + folder.file("f.json"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("aief: warning: image '" + folder.file("cut.jpg") +
                          "': the JPEG data ends before"),
            std::string::npos)
      << r.output;
  std::ifstream in(folder.file("f.json"));
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"decoder_warnings\":["), std::string::npos);
  EXPECT_NE(json.find("a file cut short"), std::string::npos);
}

TEST(Cli, EvalRegeneratesItsReportAndKeepsTheHandWrittenSection) {
  const aief::test::TempFolder folder("aief_cli_eval");
  const std::filesystem::path report = folder.path() / "report.md";
  const std::string marker =
      "<!-- hand-written below: aief eval keeps this line and all after it -->";
  std::ofstream(report) << "stale generated table\n" << marker << "\n## Notes\nmeasured by hand\n";
  const std::string dataset = std::filesystem::path(aief::test::sample_path("graf", "img1.png"))
                                  .parent_path()
                                  .parent_path()
                                  .string();
  const std::string command = "eval --dataset " + dataset +
                              " --sequences graf --pairs 1-2 --methods aief_auto --repeat 1 -o " +
                              report.string();
  for (int run_index = 0; run_index < 2;
       ++run_index) {  // twice: the section is kept once, not stacked
    const CliResult r = run(command);
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream in(report);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("stale generated table"), std::string::npos);
    EXPECT_EQ(text.find("# aief evaluation"), 0u);
    const std::size_t at = text.find(marker);
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(text.substr(at), marker + "\n## Notes\nmeasured by hand\n");
  }
}

TEST(Cli, ExtractWritesJsonYamlAndPicture) {
  const aief::test::TempFolder folder("aief_cli");
  const std::filesystem::path& dir = folder.path();
  const std::string image = aief::test::sample_path("graf", "img1.png");
  const CliResult r = run("extract " + image + " -o " + (dir / "f.json").string() + " --draw " +
                          (dir / "f.png").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1000 keypoints"), std::string::npos) << r.output;
  EXPECT_GT(std::filesystem::file_size(dir / "f.json"), 10000u);
  EXPECT_GT(std::filesystem::file_size(dir / "f.png"), 10000u);
  EXPECT_EQ(run("extract " + image + " --mode orbslam2 -o " + (dir / "f.yml").string()).status, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "f.yml"));
  const CliResult adapt =
      run("adapt " + image + " " + aief::test::sample_path("graf", "img2.png") + " -o " +
          (dir / "a.json").string() + " --plot " + (dir / "a.png").string() + " --step 1");
  EXPECT_EQ(adapt.status, 0) << adapt.output;
  std::ifstream in(dir / "a.json");
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"threshold\""), std::string::npos);
  EXPECT_NE(json.find("\"curve\""), std::string::npos);
  EXPECT_NE(json.find("\"kept_blocks\""), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "a.png"));
  const CliResult match = run("match " + image + " " + aief::test::sample_path("graf", "img2.png") +
                              " --draw " + (dir / "m.png").string());
  EXPECT_EQ(match.status, 0) << match.output;
  EXPECT_NE(match.output.find("inliers"), std::string::npos);
  const CliResult bench = run("bench " + image + " --repeat 2 --threads 1");
  EXPECT_EQ(bench.status, 0) << bench.output;
  EXPECT_NE(bench.output.find("\"aief_ms\""), std::string::npos);
  EXPECT_NE(bench.output.find("\"opencv_orb_ms\""), std::string::npos);
  const std::string second = aief::test::sample_path("graf", "img2.png");
  const CliResult bench_pair =
      run("bench " + image + " --pair " + second + " --repeat 1 --threads 1");
  EXPECT_EQ(bench_pair.status, 0) << bench_pair.output;
  EXPECT_NE(bench_pair.output.find("\"sweep_ms\""), std::string::npos);
  EXPECT_NE(bench_pair.output.find("\"pair_ms\""), std::string::npos);
  EXPECT_EQ(run("bench " + image + " --pair " + second + " --mode orbslam2 --repeat 1").status,
            2);  // no entropy, no sweep
  const CliResult validate = run("validate");
  EXPECT_EQ(validate.status, 0) << validate.output;
  EXPECT_NE(validate.output.find("identical"), std::string::npos);
}

}  // namespace

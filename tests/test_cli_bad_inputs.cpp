// The aief command line given inputs of the wrong kind: a FIFO named like an image, an image or
// a folder or /dev/zero given as a list, a picture path OpenCV cannot write, a float image.
// Each gets its reason and a non-zero exit, before any work where the flag can be checked first.
// Every command runs under `timeout`: what used to hang fails the test instead of blocking it.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/image_formats.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;

using CliResult = aief::test::CommandRun;  // status 124: killed by the timeout (it hung)

CliResult run(const std::string& arguments) {
  return aief::test::run_shell("timeout 120 " + std::string(AIEF_CLI_PATH) + " " + arguments +
                               " </dev/null");
}

bool says(const CliResult& result, const std::string& text) {
  return result.output.find(text) != std::string::npos;
}

TEST(CliBadInputs, AFifoNamedLikeAnImageIsRefusedWithoutOpeningIt) {
  const aief::test::TempFolder folder("aief_cli_fifo");
  const fs::path images = folder.path() / "images";
  fs::create_directories(images);
  ASSERT_EQ(mkfifo((images / "fifo.png").c_str(), 0600), 0);
  fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / "boat.png");

  const CliResult single = run("extract " + (images / "fifo.png").string());
  EXPECT_EQ(single.status, 1) << single.output;
  EXPECT_TRUE(says(single, "not a regular file (a FIFO)")) << single.output;

  const CliResult batch =
      run("extract --batch " + images.string() + " -o " + (folder.path() / "out").string());
  EXPECT_EQ(batch.status, 1) << batch.output;
  EXPECT_TRUE(says(batch, "1 extracted") && says(batch, "1 failed")) << batch.output;
  EXPECT_TRUE(says(batch, "fifo.png: cannot open image") &&
              says(batch, "not a regular file (a FIFO)"))
      << batch.output;
  EXPECT_TRUE(fs::exists(folder.path() / "out" / "boat.png.json"));
}

TEST(CliBadInputs, ListsThatAreNotTextFilesAreRefused) {
  const aief::test::TempFolder folder("aief_cli_lists");
  const fs::path& dir = folder.path();
  const std::string image = aief::test::sample_path("boat", "img1.png");
  const std::string out = (dir / "out").string();

  const CliResult image_as_list = run("extract --batch " + image + " -o " + out);
  EXPECT_EQ(image_as_list.status, 1) << image_as_list.output;
  EXPECT_TRUE(says(image_as_list, "is a PNG image, not a text file of names"))
      << image_as_list.output;
  EXPECT_FALSE(says(image_as_list, "failed:")) << "the PNG's bytes were taken for paths";

  const CliResult endless = run("extract --batch /dev/zero -o " + out);
  EXPECT_EQ(endless.status, 1) << endless.output;
  EXPECT_TRUE(says(endless, "binary file")) << endless.output;

  std::ofstream(dir / "long.txt") << std::string(70000, 'x');
  const CliResult long_line = run("extract --batch " + (dir / "long.txt").string() + " -o " + out);
  EXPECT_EQ(long_line.status, 1) << long_line.output;
  EXPECT_TRUE(says(long_line, "line 1 is longer than")) << long_line.output;

#ifdef AIEF_HAVE_HDF5
  const std::string features = (dir / "features.h5").string();
  ASSERT_EQ(run("extract --batch " + fs::path(image).parent_path().string() + " -o " + features +
                " --format h5")
                .status,
            0);
  for (const std::string& pairs : {dir.string(), std::string("/dev/zero"), image}) {
    const CliResult match = run("match --pairs " + pairs + " --features " + features + " -o " +
                                (dir / "m.h5").string());
    EXPECT_EQ(match.status, 1) << pairs << ": " << match.output;
    EXPECT_TRUE(says(match, "pairs file '" + pairs + "'")) << match.output;
    EXPECT_FALSE(says(match, "0 pairs matched")) << match.output;
  }
#endif
}

TEST(CliBadInputs, AYamlBatchOfOddNamesResumesInsteadOfRedoingThem) {
  const aief::test::TempFolder folder("aief_cli_yaml");
  const fs::path images = folder.path() / "images";
  fs::create_directories(images);
  for (const char* name : {"{b}.png", "[a].png", "new\nline.png", "\"quoted\".png", "- dash.png"})
    fs::copy_file(aief::test::sample_path("boat", "img1.png"), images / name);
  // A name YAML cannot hold is refused before its file is read (this one is no image at all).
  std::ofstream(images / "ctl\x01.png") << "not read";
  const std::string batch = "extract --batch '" + images.string() + "' -o '" +
                            (folder.path() / "out").string() + "' --format yml --features 100";
  const CliResult first = run(batch);
  EXPECT_EQ(first.status, 1) << first.output;
  EXPECT_TRUE(says(first, "5 extracted") && says(first, "1 failed")) << first.output;
  EXPECT_TRUE(says(first, "YAML cannot hold the image name")) << first.output;
  const CliResult second = run(batch);
  EXPECT_TRUE(says(second, "0 extracted, 5 already done, 1 failed"))
      << "outputs not read back as their own: " << second.output;
  const CliResult single = run("extract '" + (images / "missing\x02.png").string() + "' -o '" +
                               (folder.path() / "x.yml").string() + "'");
  EXPECT_EQ(single.status, 1) << single.output;
  EXPECT_TRUE(says(single, "YAML cannot hold the image name") && !says(single, "no such file"))
      << single.output;
  cv::FileStorage yaml((folder.path() / "out" / "{b}.png.yml").string(), cv::FileStorage::READ);
  EXPECT_EQ(static_cast<std::string>(yaml["source_name"]), "{b}.png");
}

TEST(CliBadInputs, PicturePathsAreCheckedBeforeAnyWork) {
  const aief::test::TempFolder folder("aief_cli_pictures");
  const std::string a = aief::test::sample_path("graf", "img1.png"),
                    b = aief::test::sample_path("graf", "img2.png");
  const std::string text = (folder.path() / "x.txt").string(),
                    nowhere = (folder.path() / "missing" / "x.png").string();
  for (const std::string& command :
       {"extract " + a + " --draw " + text, "match " + a + " " + b + " --draw " + text,
        "adapt " + a + " " + b + " --plot " + text}) {
    const CliResult result = run(command);
    EXPECT_EQ(result.status, 2) << command << "\n" << result.output;
    EXPECT_TRUE(says(result, "x.txt: a picture must end in .png")) << result.output;
    EXPECT_FALSE(says(result, "keypoints") || says(result, "inliers") || says(result, "chosen"))
        << "worked first: " << result.output;
    EXPECT_FALSE(says(result, ".cpp:")) << "OpenCV's source location: " << result.output;
  }
  const CliResult missing_folder = run("extract " + a + " --draw " + nowhere);
  EXPECT_EQ(missing_folder.status, 1) << missing_folder.output;
  EXPECT_TRUE(says(missing_folder, "does not exist") && !says(missing_folder, "keypoints"))
      << missing_folder.output;
  EXPECT_EQ(run("extract " + a + " --draw " + (folder.path() / "x.JPG").string()).status, 0)
      << "any extension OpenCV writes";
}

// Each output flag pointed at an input image, by its own name, by another spelling and through a
// hard link: refused before any work (exit 2), the image left as it was. Was: replaced, exit 0.
TEST(CliBadInputs, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  const aief::test::TempFolder folder("aief_cli_outputs_inputs");
  const fs::path& dir = folder.path();
  const fs::path dataset = dir / "dataset" / "graf";
  fs::create_directories(dataset);
  for (const char* name : {"img1.png", "img2.png", "H1to2p"})
    fs::copy_file(aief::test::sample_path("graf", name), dataset / name);
  const std::string a = (dataset / "img1.png").string(), b = (dataset / "img2.png").string();
  const std::string a_dotted = (dataset / "." / "img1.png").string();
  fs::create_hard_link(b, dir / "b_link.png");
  const std::string b_link = (dir / "b_link.png").string();
  const auto size_a = fs::file_size(a), size_b = fs::file_size(b);

  for (const std::string& command :
       {"extract " + a + " --draw " + a, "extract " + a + " --draw " + a_dotted,
        "match " + a + " " + b + " --draw " + b, "match " + a + " " + b + " --draw " + b_link,
        "adapt " + a + " " + b + " --plot " + a, "adapt " + a + " " + b + " -o " + a_dotted,
        "eval --dataset " + (dir / "dataset").string() +
            " --sequences graf --pairs 1-2 --methods orbslam2 -o " + a,
        "eval --dataset " + (dir / "dataset").string() +
            " --sequences graf --pairs 1-2 --methods orbslam2 -o " +
            (dataset / "H1to2p").string()}) {
    const CliResult result = run(command);
    EXPECT_EQ(result.status, 2) << command << "\n" << result.output;
    EXPECT_TRUE(says(result, "it would replace the input") &&
                says(result, "never writes over its inputs"))
        << command << "\n"
        << result.output;
    EXPECT_FALSE(says(result, "keypoints") || says(result, "chosen") || says(result, "evaluated"))
        << "worked first: " << result.output;
  }
  EXPECT_EQ(fs::file_size(a), size_a);
  EXPECT_EQ(fs::file_size(b), size_b);
  EXPECT_EQ(fs::file_size(dataset / "H1to2p"),
            fs::file_size(aief::test::sample_path("graf", "H1to2p")));
  EXPECT_EQ(run("extract " + a + " --draw " + (dir / "drawn.png").string()).status, 0)
      << "a new name is fine";
}

// A folder batch takes every file single-image extract reads: one list of formats
// (io/image_formats.hpp). Each readable format's file under each of its extensions is extracted
// alone and by the batch; a float-only HDR or PFM beside them is not taken. Was: .jp2 .pnm .pam
// .ras .sr .jpe .dib skipped, "0 images", exit 0.
TEST(CliBadInputs, AFolderBatchTakesEveryTypeSingleExtractReads) {
  const aief::test::TempFolder folder("aief_cli_image_types");
  const fs::path images = folder.path() / "images";
  fs::create_directories(images);
  const cv::Mat colour = cv::imread(aief::test::sample_path("graf", "img1.png"));
  cv::Mat gray;
  cv::cvtColor(colour, gray, cv::COLOR_BGR2GRAY);
  int count = 0;
  for (const aief::io::ImageFormat& format : aief::io::image_formats()) {
    // The bytes of the format, from the first extension (one OpenCV writes it by).
    const std::string first(format.extensions.front());
    const fs::path encoded = folder.path() / ("encoded" + first);
    ASSERT_TRUE(cv::imwrite(encoded.string(), first == ".pbm" ? gray : colour)) << format.name;
    if (!format.refusal.empty()) {
      fs::copy_file(encoded, images / ("float" + first));
      continue;
    }
    for (const std::string_view extension : format.extensions) {
      const fs::path image = images / ("image" + std::to_string(count++) + std::string(extension));
      fs::copy_file(encoded, image);
      const CliResult single = run("extract " + image.string());
      EXPECT_EQ(single.status, 0) << image << "\n" << single.output;
    }
  }
  const CliResult batch =
      run("extract --batch " + images.string() + " -o " + (folder.path() / "out").string());
  EXPECT_EQ(batch.status, 0) << batch.output;
  EXPECT_TRUE(says(batch, std::to_string(count) + " extracted") && says(batch, " 0 failed"))
      << batch.output;
}

// The pyramid's pixels are bounded as the decoder's image is (6 x --max-image-pixels over the
// levels): a deep pyramid of tiny steps is refused with its figure before it is built.
TEST(CliBadInputs, APyramidOfTooManyPixelsIsRefusedWithItsFigure) {
  const aief::test::TempFolder folder("aief_cli_pyramid");
  const std::string image = aief::test::sample_path("graf", "img1_center_320x240.pgm");
  const std::string out = (folder.path() / "out.json").string();
  const CliResult deep = run("extract " + image + " --scale-factor 1.001 --n-levels 32 " +
                             "--max-image-pixels 76800 -o " + out);
  EXPECT_EQ(deep.status, 1) << deep.output;
  EXPECT_TRUE(says(deep, "makes a pyramid of") && says(deep, "more than the 460800 allowed"))
      << deep.output;
  EXPECT_FALSE(fs::exists(out));
  const CliResult usual = run("extract " + image + " --max-image-pixels 76800 -o " + out);
  EXPECT_EQ(usual.status, 0) << usual.output;
}

// Outputs checked before any work: a missing folder (it failed after the work, naming a
// temporary file), an extension of another format (`merge -o x.json`, `colmap -o x.h5`, `--format
// json -o oo.h5` made a folder oo.h5), an input given as -o (`colmap ... -o f.h5` said "exists
// already").
TEST(CliBadInputs, OutputsAreCheckedBeforeAnyWork) {
  const aief::test::TempFolder folder("aief_cli_outputs");
  const fs::path& dir = folder.path();
  const std::string a = aief::test::sample_path("graf", "img1.png"),
                    b = aief::test::sample_path("graf", "img2.png");
  const std::string missing = (dir / "nodir").string();
  for (const std::string& command : {"extract " + a + " -o " + missing + "/x.json",
                                     "match " + a + " " + b + " -o " + missing + "/m.json",
                                     "adapt " + a + " " + b + " -o " + missing + "/a.json",
                                     "merge -o " + missing + "/x.h5 " + (dir / "s.h5").string()}) {
    const CliResult result = run(command);
    EXPECT_EQ(result.status, 1) << command << "\n" << result.output;
    EXPECT_TRUE(says(result, "the folder '" + missing + "' does not exist")) << result.output;
    EXPECT_FALSE(says(result, ".tmp")) << result.output;
  }
  const CliResult json_as_h5 = run("extract --batch " + (dir / "none").string() +
                                   " --format json -o " + (dir / "oo.h5").string());
  EXPECT_EQ(json_as_h5.status, 2) << json_as_h5.output;
  EXPECT_TRUE(says(json_as_h5, "names h5 by its extension, but --format json"))
      << json_as_h5.output;
  EXPECT_FALSE(fs::exists(dir / "oo.h5"));
  const CliResult merge_json = run("merge -o " + (dir / "x.json").string() + " s.h5");
  EXPECT_EQ(merge_json.status, 2) << merge_json.output;
  EXPECT_TRUE(says(merge_json, "must end in .h5")) << merge_json.output;
  for (const char* name : {"f.h5", "m.h5", "pairs.txt"}) std::ofstream(dir / name) << "x";
  const std::string colmap = "colmap --features-file " + (dir / "f.h5").string() + " --matches " +
                             (dir / "m.h5").string() + " --pairs " + (dir / "pairs.txt").string();
  const CliResult database_as_h5 = run(colmap + " -o " + (dir / "x.h5").string());
  EXPECT_EQ(database_as_h5.status, 2) << database_as_h5.output;
  EXPECT_TRUE(says(database_as_h5, "must end in .db")) << database_as_h5.output;
  const CliResult onto_features = run(colmap + " -o " + (dir / "f.h5").string());
  EXPECT_EQ(onto_features.status, 1) << onto_features.output;
  EXPECT_TRUE(says(onto_features,
                   "-o '" + (dir / "f.h5").string() + "' is the features file (--features-file"))
      << onto_features.output;
  EXPECT_FALSE(says(onto_features, "exists already")) << onto_features.output;
}

}  // namespace

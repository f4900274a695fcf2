// Which descriptor features hold (ExtractorOptions::descriptor, --descriptor): every feature
// file's option record says it, and every front end that matches two feature sets refuses an
// rBRIEF set against a box set, naming both (a Hamming distance between them means nothing).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/extractor.hpp"
#include "aief/feature2d.hpp"
#include "aief/match.hpp"
#include "core/description/level_descriptor.hpp"
#include "core/options/option_names.hpp"
#include "io/feature_formats.hpp"
#include "io/hdf5_file.hpp"
#include "io/option_record.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

test::CommandRun run(const std::string& arguments) {
  return test::run_shell(std::string(AIEF_CLI_PATH) + " " + arguments);
}

ImageView view_of(const cv::Mat& gray) {
  return {gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)};
}

ExtractorOptions with_descriptor(DescriptorKind descriptor) {
  ExtractorOptions options;
  options.n_features = 200;
  options.descriptor = descriptor;
  return options;
}

TEST(DescriptorKinds, FeaturesSayWhichDescriptorTheyHold) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  for (DescriptorKind kind : {DescriptorKind::rbrief, DescriptorKind::box}) {
    Extractor extractor(with_descriptor(kind));
    const Features extracted = extractor.extract(view_of(image));
    EXPECT_EQ(extracted.descriptor, kind);
    EXPECT_EQ(extractor.describe(view_of(image), extracted.keypoints).descriptor, kind);
  }
  EXPECT_EQ(ExtractorOptions{}.descriptor, DescriptorKind::rbrief);
  for (Mode mode :
       {Mode::aief, Mode::aief_paper, Mode::orbslam2, Mode::quadtree_entropy, Mode::faithful})
    EXPECT_EQ(options_for_mode(mode).descriptor, DescriptorKind::rbrief) << to_string(mode);
}

TEST(DescriptorKinds, BoxDescriptorsDifferFromRbriefOnTheSameKeypoints) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  const Features rbrief =
      Extractor(with_descriptor(DescriptorKind::rbrief)).extract(view_of(image));
  const Features box = Extractor(with_descriptor(DescriptorKind::box)).extract(view_of(image));
  ASSERT_EQ(rbrief.keypoints.size(), box.keypoints.size());  // detection does not depend on it
  for (std::size_t i = 0; i < rbrief.keypoints.size(); ++i)
    EXPECT_EQ(rbrief.keypoints[i].x, box.keypoints[i].x);
  EXPECT_NE(rbrief.descriptors, box.descriptors);
}

// Every descriptor a name table holds (core/options/option_names.hpp), so a new one is tested here
// without a line of its own.
std::vector<DescriptorKind> every_kind() {
  std::vector<DescriptorKind> kinds;
  for (const auto& name : option_names::Table<DescriptorKind>::names) kinds.push_back(name.value);
  return kinds;
}

// Every kind has its strategy, the row of core/description/level_descriptor.hpp that describes
// it in extraction and in Extractor::describe alike.
TEST(DescriptorKinds, EveryKindHasItsDescriptorRow) {
  ASSERT_GE(every_kind().size(), 2u);  // rbrief, box, ...
  for (DescriptorKind kind : every_kind())
    EXPECT_EQ(kind_of(level_descriptor_of(kind)), kind) << to_string(kind);
}

// Given keypoints in any order (the descriptor's band walks a level in raster order, so describe
// sorts each level's keypoints first) get the descriptors extract gave them, in their given order.
TEST(DescriptorKinds, DescribingKeypointsInAnyOrderGivesExtractsBytes) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  for (DescriptorKind kind : every_kind()) {
    SCOPED_TRACE(to_string(kind));
    Extractor extractor(with_descriptor(kind));
    const Features extracted = extractor.extract(view_of(image));
    std::vector<std::size_t> order(extracted.keypoints.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    std::vector<Keypoint> shuffled;
    for (std::size_t i : order) shuffled.push_back(extracted.keypoints[i]);
    shuffled.push_back(shuffled.front());  // a keypoint given twice is described twice
    order.push_back(order.front());
    const Features described = extractor.describe(view_of(image), shuffled);
    ASSERT_EQ(described.keypoints.size(), shuffled.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      EXPECT_EQ(described.descriptors[k], extracted.descriptors[order[k]]) << "keypoint " << k;
  }
}

TEST(DescriptorKinds, Feature2DTakesTheOption) {
  const cv::Mat image = test::load_sample_gray("graf", "img1.png");
  const ExtractorOptions options = with_descriptor(DescriptorKind::box);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  opencv::Feature2D::create(options)->detectAndCompute(image, cv::noArray(), keypoints,
                                                       descriptors);
  const Features expected = Extractor(options).extract(view_of(image));
  ASSERT_EQ(static_cast<std::size_t>(descriptors.rows), expected.descriptors.size());
  for (int i = 0; i < descriptors.rows; ++i)
    EXPECT_TRUE(std::equal(expected.descriptors[static_cast<std::size_t>(i)].begin(),
                           expected.descriptors[static_cast<std::size_t>(i)].end(),
                           descriptors.ptr<std::uint8_t>(i)))
        << "row " << i;
}

TEST(DescriptorKinds, MatchingDifferentKindsIsRefusedNamingBoth) {
  EXPECT_NO_THROW(require_same_descriptor(DescriptorKind::box, "a", DescriptorKind::box, "b"));
  try {
    require_same_descriptor(DescriptorKind::rbrief, "'a.png'", DescriptorKind::box, "'b.png'");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'a.png' holds rbrief descriptors, 'b.png' box "
                                         "descriptors: they cannot be matched"),
              std::string::npos)
        << e.what();
  }
}

TEST(DescriptorKinds, RecordsWithoutTheFieldHoldRbrief) {
  EXPECT_EQ(io::recorded_descriptor(std::nullopt), DescriptorKind::rbrief);
  EXPECT_EQ(io::recorded_descriptor(std::string("{\"n_features\":1000}")), DescriptorKind::rbrief);
  EXPECT_EQ(io::recorded_descriptor(std::string("{\"n_features\":1000,\"descriptor\":\"box\"}")),
            DescriptorKind::box);
  EXPECT_THROW(io::recorded_descriptor(std::string("{\"descriptor\":\"sift\"}")), Error);
}

TEST(DescriptorKinds, EveryFileFormatRecordsTheDescriptor) {
  test::TempFolder folder("aief_descriptor_kinds");
  const std::string image = test::sample_path("graf", "img1.png");
  for (const char* extension : {".json", ".yml", ".npz", ".h5"}) {
    const std::string out = folder.file(std::string("f") + extension);
    const bool h5 = std::string(extension) == ".h5";  // hloc's file holds a batch
    if (h5) {
      std::filesystem::create_directories(folder.file("images"));
      std::filesystem::copy_file(image, folder.file("images/img1.png"));
    }
    const test::CommandRun r =
        run("extract " + (h5 ? "--batch " + folder.file("images") + " --format h5" : image) +
            " --n-features 100 --descriptor box -o " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    std::optional<std::string> record;
    if (h5) {
      const io::Hdf5File file(out, io::Hdf5File::Mode::read);
      const std::string name = file.feature_names().at(0);
      record = file.option_record(name);
      EXPECT_EQ(file.read_features(name).descriptor, DescriptorKind::box);
    } else {
      const io::FeatureFormat* format = io::feature_format_of_path(out);
      ASSERT_NE(format, nullptr);
      io::SourceRecord source;
      source.name = "img1.png";
      record = format->record(out, source).options;
    }
    ASSERT_TRUE(record.has_value()) << extension;
    EXPECT_EQ(io::recorded_descriptor(record), DescriptorKind::box) << extension << " " << *record;
  }
}

// An hloc features file whose images hold different descriptors (written image by image, as two
// runs or a Dask recipe could): match --pairs and the COLMAP export refuse it.
class MixedFeaturesFile : public ::testing::Test {
 protected:
  MixedFeaturesFile() : folder_("aief_descriptor_kinds_mixed") {
    io::Hdf5File file(features(), io::Hdf5File::Mode::read_write);
    for (const auto& [name, kind] :
         {std::pair{"a.png", DescriptorKind::rbrief}, std::pair{"b.png", DescriptorKind::box}}) {
      const cv::Mat image = test::load_sample_gray("graf", "img1.png");
      const ExtractorOptions options = with_descriptor(kind);
      const Features f = Extractor(options).extract(view_of(image));
      file.write_features(name, f, nullptr, &options);
    }
    file.close();
    std::ofstream(pairs()) << "a.png b.png\n";
  }
  std::string features() const { return folder_.file("features.h5"); }
  std::string pairs() const { return folder_.file("pairs.txt"); }
  test::TempFolder folder_;
};

TEST_F(MixedFeaturesFile, MatchPairsRefusesNamingBothImages) {
  const test::CommandRun r = run("match --pairs " + pairs() + " --features-file " + features() +
                                 " -o " + folder_.file("matches.h5"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("aief: error: 'a.png' holds rbrief descriptors, 'b.png' (both in '" +
                          features() + "') box descriptors: they cannot be matched"),
            std::string::npos)
      << r.output;
}

TEST_F(MixedFeaturesFile, ColmapExportRefusesNamingBothImages) {
  io::Hdf5File(folder_.file("matches.h5"), io::Hdf5File::Mode::read_write).close();  // no pairs
  const test::CommandRun r =
      run("colmap --features-file " + features() + " --matches " + folder_.file("matches.h5") +
          " --pairs " + pairs() + " -o " + folder_.file("database.db"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("holds rbrief descriptors"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("box descriptors: they cannot be matched"), std::string::npos)
      << r.output;
}

TEST(DescriptorKinds, MergeRefusesShardsOfDifferentDescriptors) {
  test::TempFolder folder("aief_descriptor_kinds_merge");
  const std::string image = test::sample_path("graf", "img1.png");
  std::filesystem::create_directories(folder.file("one"));
  std::filesystem::create_directories(folder.file("two"));
  std::filesystem::copy_file(image, folder.file("one/a.png"));
  std::filesystem::copy_file(test::sample_path("graf", "img2.png"), folder.file("two/b.png"));
  ASSERT_EQ(run("extract --batch " + folder.file("one") + " --n-features 100 --format h5 -o " +
                folder.file("one.h5"))
                .status,
            0);
  ASSERT_EQ(run("extract --batch " + folder.file("two") +
                " --n-features 100 --descriptor box --format h5 -o " + folder.file("two.h5"))
                .status,
            0);
  const test::CommandRun r = run("merge -o " + folder.file("all.h5") + " " + folder.file("one.h5") +
                                 " " + folder.file("two.h5"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("descriptor rbrief -> box"), std::string::npos) << r.output;
}

// Before: `extract --batch imgs -o rbrief.h5 --descriptor box --shard 0/2` into a file of rBRIEF
// features exited 0, the file then held both, and a note called the other shard's images
// "deleted or moved?".
TEST(DescriptorKinds, AShardedBatchOfAnotherDescriptorIntoAFileIsRefused) {
  test::TempFolder folder("aief_descriptor_kinds_shard");
  std::filesystem::create_directories(folder.file("imgs"));
  std::filesystem::copy_file(test::sample_path("graf", "img1.png"), folder.file("imgs/a.png"));
  std::filesystem::copy_file(test::sample_path("graf", "img2.png"), folder.file("imgs/b.png"));
  const std::string batch = "extract --batch " + folder.file("imgs") +
                            " --n-features 100 --format h5 -o " + folder.file("rbrief.h5");
  ASSERT_EQ(run(batch).status, 0);
  const test::CommandRun r = run(batch + " --descriptor box --shard 0/2");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("holds rbrief descriptors (image 'b.png'"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("this run extracts box descriptors"), std::string::npos) << r.output;
  {
    const io::Hdf5File file(folder.file("rbrief.h5"), io::Hdf5File::Mode::read);
    for (const std::string& name : file.feature_names())
      EXPECT_EQ(io::recorded_descriptor(file.option_record(name)), DescriptorKind::rbrief) << name;
  }
  // The whole folder again with the box descriptor replaces every image: nothing is mixed.
  EXPECT_EQ(run(batch + " --descriptor box").status, 0);
}

}  // namespace
}  // namespace aief

// Result files: JSON and OpenCV YAML carry every keypoint and descriptor (read back with
// OpenCV's reader), every odd image name round-trips, control characters are refused clearly.
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/feature_formats.hpp"
#include "io/image_io.hpp"
#include "tests/odd_names.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using TempDir = test::TempFolder;

TEST(FeatureFiles, JsonAndYamlCarryEveryKeypointAndDescriptor) {
  TempDir dir;
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  ExtractorOptions options;
  options.n_features = 200;
  const Features features = extract(view_of(gray), options);
  ASSERT_GT(features.keypoints.size(), 100u);

  io::write_features(dir.file("f.json"), "boat.png", features, options);
  std::ifstream in(dir.file("f.json"));
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"image\":\"boat.png\""), std::string::npos);
  EXPECT_NE(json.find("\"width\":850"), std::string::npos);
  EXPECT_NE(json.find("\"n_features\":200"), std::string::npos);
  std::size_t hex_strings = 0, keypoints = 0;
  for (std::size_t at = json.find("\"octave\""); at != std::string::npos;
       at = json.find("\"octave\"", at + 1))
    ++keypoints;
  const std::size_t list = json.find("\"descriptors_hex\"");
  for (std::size_t at = json.find('"', list + 18); at != std::string::npos;
       at = json.find('"', at + 66)) {
    ASSERT_EQ(json[at + 65], '"') << "descriptor string of 64 hex characters";
    ++hex_strings;
  }
  EXPECT_EQ(keypoints, features.keypoints.size());
  EXPECT_EQ(hex_strings, features.descriptors.size());
  EXPECT_FALSE(std::filesystem::exists(dir.file("f.json.tmp")));

  io::write_features(dir.file("f.yml"), "boat.png", features, options);
  cv::FileStorage fs(dir.file("f.yml"), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  std::vector<cv::KeyPoint> keypoints_back;
  cv::read(fs["keypoints"], keypoints_back);
  cv::Mat descriptors;
  fs["descriptors"] >> descriptors;
  ASSERT_EQ(keypoints_back.size(), features.keypoints.size());
  ASSERT_EQ(descriptors.rows, static_cast<int>(features.descriptors.size()));
  ASSERT_EQ(descriptors.cols, 32);
  ASSERT_EQ(descriptors.type(), CV_8U);
  for (std::size_t i = 0; i < keypoints_back.size(); ++i) {
    EXPECT_EQ(keypoints_back[i].pt.x, features.keypoints[i].x);
    EXPECT_EQ(keypoints_back[i].octave, features.keypoints[i].octave);
    EXPECT_EQ(
        0, std::memcmp(descriptors.ptr(static_cast<int>(i)), features.descriptors[i].data(), 32));
  }
  EXPECT_THROW(io::write_features(dir.file("f.txt"), "x", features, options), Error);
}

TEST(FeatureFiles, YamlRoundTripsEveryOddNameAndRefusesControlCharactersClearly) {
  TempDir dir;
  const GrayImage image = io::read_gray_image(test::sample_path("boat", "img1.png"));
  ExtractorOptions options;
  options.n_features = 50;
  const Features features = extract(image.view(), options);
  int file = 0;
  for (const std::string& name : test::odd_image_names()) {
    io::SourceRecord source{name, 1234, 5678, {}};
    for (const char* extension : {".yml", ".json", ".npz"}) {
      const std::string path = dir.file(std::to_string(file++) + extension);
      ASSERT_NO_THROW(io::write_features(path, name, features, options, source)) << name;
      EXPECT_TRUE(io::features_file_belongs_to(path, source))
          << extension << " '" << name << "' read back as another name";
      source.bytes += 1;
      EXPECT_FALSE(io::features_file_belongs_to(path, source)) << name;
      source.bytes -= 1;
      if (std::string(extension) != ".yml") continue;
      cv::FileStorage fs(path, cv::FileStorage::READ);
      ASSERT_TRUE(fs.isOpened()) << name;
      EXPECT_EQ(static_cast<std::string>(fs["image"]), name);
      EXPECT_EQ(static_cast<std::string>(fs["source_name"]), name);
      cv::Mat descriptors;
      fs["descriptors"] >> descriptors;
      EXPECT_EQ(descriptors.rows, static_cast<int>(features.descriptors.size())) << name;
    }
  }
  for (const std::string& name : test::control_character_names()) {
    const io::SourceRecord source{name, 1, 2, {}};
    try {
      io::write_features(dir.file("control.yml"), name, features, options, source);
      ADD_FAILURE() << "YAML accepted a name it cannot read back";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("YAML cannot hold the image name"), std::string::npos)
          << e.what();
      // The formats that can, from the registry's rows (io/feature_formats.cpp).
      EXPECT_NE(std::string(e.what()).find("(write .json or .npz for such names)"),
                std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("control.yml")));
    io::write_features(dir.file("control.json"), name, features, options, source);
    EXPECT_TRUE(io::features_file_belongs_to(dir.file("control.json"), source));
  }
  // Longer than OpenCV's YAML strings (4094 bytes), escapes counted: refused, not cut.
  const std::string long_name = std::string(2100, 'a') + std::string(1000, '"') + ".png";
  EXPECT_THROW(io::write_features(dir.file("long.yml"), long_name, features, options,
                                  io::SourceRecord{long_name, 1, 2, {}}),
               Error);
}

}  // namespace
}  // namespace aief

// Image reading (conversions, clear errors) and result files (JSON, OpenCV YAML read back).
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/features_files.hpp"
#include "io/image_io.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using TempDir = test::TempFolder;

std::string error_of(const std::string& path) {
  try {
    io::read_gray_image(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImageIo, ReadsGrayAndConvertsColourDepthAndAlpha) {
  TempDir dir;
  cv::Mat colour(20, 30, CV_8UC3);
  cv::randu(colour, 0, 255);
  cv::imwrite(dir.file("c.png"), colour);
  cv::Mat expected;
  cv::cvtColor(colour, expected, cv::COLOR_BGR2GRAY);
  GrayImage gray = io::read_gray_image(dir.file("c.png"));
  ASSERT_EQ(gray.width(), 30);
  ASSERT_EQ(gray.height(), 20);
  EXPECT_EQ(0, std::memcmp(gray.data(), expected.data, 600));

  cv::Mat rgba(10, 12, CV_8UC4, cv::Scalar(10, 20, 30, 0));
  cv::imwrite(dir.file("a.png"), rgba);
  EXPECT_EQ(io::read_gray_image(dir.file("a.png")).width(), 12);

  cv::Mat real(8, 9, CV_32FC1, cv::Scalar(0.5));  // float images are refused with the depth named
  cv::imwrite(dir.file("f.tiff"), real);
  EXPECT_NE(error_of(dir.file("f.tiff")).find("not 8- or 16-bit unsigned"), std::string::npos);

  cv::Mat deep(8, 9, CV_16UC1, cv::Scalar(51200));  // 200 * 256
  cv::imwrite(dir.file("d.png"), deep);
  const GrayImage eight = io::read_gray_image(dir.file("d.png"));
  EXPECT_EQ(eight.data()[0], 200);
}

TEST(ImageIo, ClearErrorsForBadFiles) {
  TempDir dir;
  EXPECT_NE(error_of(dir.file("missing.png")).find("no such file"), std::string::npos);
  EXPECT_NE(error_of(dir.path().string()).find("directory"), std::string::npos);
  std::ofstream(dir.file("text.png")) << "this is not an image";
  EXPECT_NE(error_of(dir.file("text.png")).find("cannot read image"), std::string::npos);
  // Truncated PNG and JPEG: the first part of a valid file.
  for (const char* ext : {".png", ".jpg"}) {
    std::vector<std::uint8_t> bytes;
    cv::imencode(ext, test::random_image(64, 64, 3), bytes);
    std::ofstream out(dir.file(std::string("cut") + ext), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size() / 3));
    out.close();
    std::string message;
    try {
      const GrayImage image = io::read_gray_image(dir.file(std::string("cut") + ext));
      message = "decoded " + std::to_string(image.width());  // libjpeg pads a cut file: an image, no crash
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_FALSE(message.empty()) << ext;
  }
}

TEST(FeatureFiles, JsonAndYamlCarryEveryKeypointAndDescriptor) {
  TempDir dir;
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  ExtractorOptions options;
  options.n_features = 200;
  const Features features = extract(test::view_of(gray), options);
  ASSERT_GT(features.keypoints.size(), 100u);

  io::write_features(dir.file("f.json"), "boat.png", features, options);
  std::ifstream in(dir.file("f.json"));
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"image\":\"boat.png\""), std::string::npos);
  EXPECT_NE(json.find("\"width\":850"), std::string::npos);
  EXPECT_NE(json.find("\"n_features\":200"), std::string::npos);
  std::size_t hex_strings = 0, keypoints = 0;
  for (std::size_t at = json.find("\"octave\""); at != std::string::npos; at = json.find("\"octave\"", at + 1)) ++keypoints;
  const std::size_t list = json.find("\"descriptors_hex\"");
  for (std::size_t at = json.find('"', list + 18); at != std::string::npos; at = json.find('"', at + 66)) {
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
    EXPECT_EQ(0, std::memcmp(descriptors.ptr(static_cast<int>(i)), features.descriptors[i].data(), 32));
  }
  EXPECT_THROW(io::write_features(dir.file("f.txt"), "x", features, options), Error);
}

}  // namespace
}  // namespace aief

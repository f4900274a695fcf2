#include "tests/io_test_support.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/image_io.hpp"
#include "tests/test_support.hpp"

namespace aief::test {

std::string error_of(const std::string& path) {
  try {
    io::read_gray_image(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::vector<std::uint8_t> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
}

Features sample_features(const char* sequence, int index) {
  const GrayImage image =
      io::read_gray_image(test::sample_path(sequence, "img" + std::to_string(index) + ".png"));
  return extract(image.view());
}

std::vector<std::string> temporaries_in(const std::string& folder) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name[0] == '.' && name.find(".tmp") != std::string::npos) found.push_back(name);
  }
  return found;
}

void expect_same(const Features& a, const Features& b) {
  ASSERT_EQ(a.keypoints.size(), b.keypoints.size());
  EXPECT_EQ(a.image_width, b.image_width);
  EXPECT_EQ(a.image_height, b.image_height);
  for (std::size_t i = 0; i < a.keypoints.size(); ++i) {
    EXPECT_EQ(a.keypoints[i].x, b.keypoints[i].x) << i;
    EXPECT_EQ(a.keypoints[i].y, b.keypoints[i].y) << i;
    EXPECT_EQ(a.keypoints[i].size, b.keypoints[i].size) << i;
    EXPECT_EQ(a.keypoints[i].angle_deg, b.keypoints[i].angle_deg) << i;
    EXPECT_EQ(a.keypoints[i].response, b.keypoints[i].response) << i;
    EXPECT_EQ(a.keypoints[i].octave, b.keypoints[i].octave) << i;
  }
  EXPECT_EQ(a.descriptors, b.descriptors);
}

}  // namespace aief::test

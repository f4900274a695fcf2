#include "tests/test_support.hpp"

#include <cstdlib>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace aief::test {

std::string sample_path(const std::string& sequence, const std::string& file) {
  return std::string(AIEF_SAMPLE_DIR) + "/" + sequence + "/" + file;
}

cv::Mat load_sample_gray(const std::string& sequence, const std::string& file) {
  const std::string path = sample_path(sequence, file);
  cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  EXPECT_FALSE(image.empty()) << "missing sample " << path;
  if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
  return image;
}

cv::Mat random_image(int width, int height, std::uint32_t seed) {
  cv::Mat image(height, width, CV_8UC1);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, 255);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(value(rng));
  return image;
}

cv::Mat random_textured_image(int width, int height, std::uint32_t seed) {
  cv::Mat noise = random_image(width, height, seed);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(5, 5), 1.5);
  cv::normalize(smooth, smooth, 0, 255, cv::NORM_MINMAX);
  return smooth;
}

TempFolder::TempFolder(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
  path_ = pattern;
}

TempFolder::~TempFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace aief::test

#pragma once
// Shared by the tests: seeded random images and the bundled sample images.
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "aief/image.hpp"

namespace aief::test {

// Path of a bundled sample, e.g. sample_path("graf", "img1.png").
std::string sample_path(const std::string& sequence, const std::string& file);

// The bundled sample as 8-bit gray (OpenCV's cvtColor BGR2GRAY); fails the test if missing.
cv::Mat load_sample_gray(const std::string& sequence, const std::string& file);

// Uniform random u8 image, reproducible from the seed.
cv::Mat random_image(int width, int height, std::uint32_t seed);

// Random image smoothed and contrast-stretched so it has corners of every strength.
cv::Mat random_textured_image(int width, int height, std::uint32_t seed);

inline ImageView view_of(const cv::Mat& gray) {
  return {gray.data, gray.cols, gray.rows, static_cast<std::ptrdiff_t>(gray.step)};
}

}  // namespace aief::test

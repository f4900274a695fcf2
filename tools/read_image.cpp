#include "tools/read_image.hpp"

#include <iostream>

#include "io/image_io.hpp"

namespace aief::cli {

GrayImage read_image_reporting(const std::string& path, long long max_pixels,
                               std::vector<std::string>* warnings) {
  std::vector<std::string> found;
  GrayImage image = io::read_gray_image(path, max_pixels, &found);
  for (const std::string& warning : found) std::cerr << "aief: warning: " << warning << "\n";
  if (warnings) warnings->insert(warnings->end(), found.begin(), found.end());
  return image;
}

}  // namespace aief::cli

#pragma once
// An image file for a command: io::read_gray_image, whose warnings (a JPEG cut short, ...) are
// printed as "aief: warning: ..." on stderr and, when asked, returned for the result file.
#include <string>
#include <vector>

#include "aief/image.hpp"

namespace aief::cli {

GrayImage read_image_reporting(const std::string& path, long long max_pixels,
                               std::vector<std::string>* warnings = nullptr);

}  // namespace aief::cli

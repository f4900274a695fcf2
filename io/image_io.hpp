#pragma once
// Image files in: anything OpenCV's imgcodecs reads, as 8-bit gray.
//
// Conversion: 3- and 4-channel images -> gray by OpenCV's cvtColor (ITU-R BT.601 luma,
// 0.299 R + 0.587 G + 0.114 B, OpenCV's fixed point); 16-bit images -> 8 bits, divided by 256
// and rounded; other depths (float, signed) are refused. Errors are aief::Error naming the path.
#include <cstdint>
#include <string>
#include <vector>

#include "aief/image.hpp"

namespace aief::io {

GrayImage read_gray_image(const std::string& path);

// The same conversion for an image already in memory as encoded bytes (PNG, JPEG, ...);
// `name` goes into the error messages.
GrayImage decode_gray_image(const std::vector<std::uint8_t>& bytes, const std::string& name);

}  // namespace aief::io

#pragma once
// The image formats aief knows, and which of them it reads: one list behind the single-image
// reader (io/image_io.cpp decodes a file whose header, io/image_header.hpp, names a format read
// here, whatever its extension, and refuses the others by name) and the folder batch
// (io/batch_inputs.hpp takes the files with an extension of a format read here). Extensions are
// those OpenCV's imgcodecs gives these formats, and the JPEG 2000 codestream's.
#include <string>
#include <string_view>
#include <vector>

namespace aief::io {

struct ImageFormat {
  std::string_view name;  // as io::ImageHeader::format names it: "PNG", "JPEG 2000", ...
  std::vector<std::string_view> extensions;  // lower case, with the dot
  // Empty: read. Otherwise why it is not (formats of floating-point pixels only).
  std::string_view refusal;
};

const std::vector<ImageFormat>& image_formats();

// The entry of `name` (an ImageHeader::format), or nullptr.
const ImageFormat* image_format_named(std::string_view name);

// Whether `path`'s extension (any case) is one of a format aief reads.
bool has_readable_image_extension(const std::string& path);

// "PNG, JPEG, TIFF, ..." (the formats read), for messages.
std::string readable_image_format_names();

}  // namespace aief::io

#include "io/image_formats.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace aief::io {

const std::vector<ImageFormat>& image_formats() {
  static const std::vector<ImageFormat> formats = {
      {"PNG", {".png"}, ""},
      {"JPEG", {".jpg", ".jpeg", ".jpe"}, ""},
      {"TIFF", {".tif", ".tiff"}, ""},
      {"WebP", {".webp"}, ""},
      {"BMP", {".bmp", ".dib"}, ""},
      {"PNM", {".pbm", ".pgm", ".ppm", ".pnm", ".pxm"}, ""},
      {"PAM", {".pam"}, ""},
      {"Sun raster", {".sr", ".ras"}, ""},
      {"JPEG 2000", {".jp2", ".j2k", ".j2c", ".jpc"}, ""},
      {"HDR", {".hdr", ".pic"}, "a Radiance HDR file holds floating-point pixels"},
      {"PFM", {".pfm"}, "a PFM file holds floating-point pixels"},
  };
  return formats;
}

const ImageFormat* image_format_named(std::string_view name) {
  for (const ImageFormat& format : image_formats())
    if (format.name == name) return &format;
  return nullptr;
}

bool has_readable_image_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const ImageFormat& format : image_formats())
    if (format.refusal.empty() && std::find(format.extensions.begin(), format.extensions.end(),
                                            extension) != format.extensions.end())
      return true;
  return false;
}

std::string readable_image_format_names() {
  std::string names;
  for (const ImageFormat& format : image_formats()) {
    if (!format.refusal.empty()) continue;
    if (!names.empty()) names += ", ";
    names += format.name;
  }
  return names;
}

}  // namespace aief::io

#include "io/image_io.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "io/image_header.hpp"

namespace aief::io {

namespace {

// 8-bit gray from whatever OpenCV decoded (see the header for the conversions).
GrayImage gray_from_decoded(cv::Mat image, const std::string& path) {
  if (image.depth() == CV_16U) {
    image.convertTo(image, CV_8U, 1.0 / 256.0);
  } else if (image.depth() != CV_8U) {
    throw Error("cannot use image '" + path + "': pixel depth " + std::to_string(image.depth()) +
                " is not 8- or 16-bit unsigned");
  }
  // The conversion writes straight into the result: no second full-size gray copy at the peak.
  GrayImage out(image.cols, image.rows);
  cv::Mat gray(out.height(), out.width(), CV_8UC1, out.data());
  switch (image.channels()) {
    case 1: image.copyTo(gray); break;
    case 3: cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY); break;
    case 4: cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY); break;
    default:
      throw Error("cannot use image '" + path + "': " + std::to_string(image.channels()) + " channels (expected 1, 3 or 4)");
  }
  CV_Assert(gray.data == out.data());  // OpenCV kept the buffer it was given
  return out;
}

// Refuses what cannot be decoded safely: an unknown format, or more pixels than allowed.
void check_declared_size(const std::vector<std::uint8_t>& bytes, const std::string& name, long long max_pixels) {
  const std::optional<ImageHeader> header = read_image_header(bytes.data(), bytes.size());
  if (!header)
    throw Error("cannot read image '" + name +
                "': not an image aief can read (PNG, JPEG, TIFF, WebP, BMP, PNM/PAM/PFM, Sun raster, Radiance HDR, "
                "JPEG 2000), or its header is damaged");
  // Compared by division: width x height may not fit in 64 bits.
  if (header->width > 0 && header->height > max_pixels / header->width)
    throw Error("image '" + name + "' declares " + std::to_string(header->width) + "x" + std::to_string(header->height) +
                " pixels in its " + header->format + " header, more than max_image_pixels = " +
                std::to_string(max_pixels) + " (refused before decoding)");
}

}  // namespace

GrayImage read_gray_image(const std::string& path, long long max_pixels) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("cannot open image '" + path + "': no such file");
  if (std::filesystem::is_directory(path, ec)) throw Error("cannot open image '" + path + "': it is a directory");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error("cannot open image '" + path + "': permission denied");
  // The encoded bytes in memory (a fraction of the decoded size): the header is checked first.
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(std::max<std::streamoff>(in.tellg(), 0)));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!in) throw Error("cannot read image '" + path + "': read error");
  return decode_gray_image(bytes, path, max_pixels);
}

GrayImage decode_gray_image(const std::vector<std::uint8_t>& bytes, const std::string& name, long long max_pixels) {
  check_declared_size(bytes, name, max_pixels);
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    // The decoder's own message only, not OpenCV's source location and assertion text.
    throw Error("cannot read image '" + name + "': the decoder failed (" + e.err + ")");
  }
  if (image.empty()) throw Error("cannot read image '" + name + "': not an image OpenCV can decode, or a damaged file");
  return gray_from_decoded(image, name);
}

GrayImage gray_from_pixels(const std::uint8_t* pixels, int width, int height, int channels, std::ptrdiff_t row_stride,
                           const std::string& name) {
  if (width <= 0 || height <= 0 || pixels == nullptr)
    throw Error("cannot use image '" + name + "': it is empty (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  if (channels != 1 && channels != 3 && channels != 4)
    throw Error("cannot use image '" + name + "': " + std::to_string(channels) + " channels (expected 1, 3 or 4)");
  // A header over the caller's bytes (OpenCV does not write through it): the conversion is the
  // one read_gray_image applies to a decoded file.
  const cv::Mat image(height, width, CV_8UC(channels), const_cast<std::uint8_t*>(pixels), static_cast<std::size_t>(row_stride));
  return gray_from_decoded(image, name);
}

}  // namespace aief::io

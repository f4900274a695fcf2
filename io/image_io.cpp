#include "io/image_io.hpp"

#include <algorithm>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "io/encoded_bytes.hpp"
#include "io/image_extent.hpp"
#include "io/image_formats.hpp"
#include "io/image_header.hpp"

namespace aief::io {

namespace {

std::string depth_name(int depth) {
  switch (depth) {
    case CV_8S: return "8-bit signed";
    case CV_16S: return "16-bit signed";
    case CV_32S: return "32-bit signed integer";
    case CV_16F: return "16-bit float";
    case CV_32F: return "32-bit float";
    case CV_64F: return "64-bit float";
    default: return "depth " + std::to_string(depth);
  }
}

// 8-bit gray from whatever OpenCV decoded (see the header for the conversions).
GrayImage gray_from_decoded(cv::Mat image, const std::string& path) {
  if (image.depth() == CV_16U) {
    image.convertTo(image, CV_8U, 1.0 / 256.0);
  } else if (image.depth() != CV_8U) {
    throw Error(
        "cannot use image '" + path + "': its pixels are " + depth_name(image.depth()) +
        ", not 8- or 16-bit unsigned (no conversion is right for every use: convert it first)");
  }
  // The conversion writes straight into the result: no second full-size gray copy at the peak.
  GrayImage out(image.cols, image.rows);
  cv::Mat gray(out.height(), out.width(), CV_8UC1, out.data());
  switch (image.channels()) {
    case 1: image.copyTo(gray); break;
    case 3: cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY); break;
    case 4: cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY); break;
    default:
      throw Error("cannot use image '" + path + "': " + std::to_string(image.channels()) +
                  " channels (expected 1, 3 or 4)");
  }
  CV_Assert(gray.data == out.data());  // OpenCV kept the buffer it was given
  return out;
}

constexpr long long kMaxDecodedBytesPerPixel = 4;  // 8-bit BGRA
// The scan limit libjpeg-turbo's own tools and fuzz targets set (djpeg -maxscans).
constexpr long long kMaxJpegScans = 500;

// Refuses what cannot be decoded safely or used: more pixels than allowed, a format of float
// pixels.
void check_header(const ImageHeader* header, const std::string& name, long long max_pixels) {
  // Compared by division: width x height may not fit in 64 bits.
  if (header->width > 0 && header->height > max_pixels / header->width)
    throw Error("image '" + name + "' declares " + std::to_string(header->width) + "x" +
                std::to_string(header->height) + " pixels in its " + header->format +
                " header, more than max_image_pixels = " + std::to_string(max_pixels) +
                " (refused before decoding)");
  // What the decoder allocates is bytes, not pixels: a 16-bit RGBA PNG takes 8 bytes a pixel
  // (522 KB of PNG decoded to 0.9 GB at the pixel limit). The bytes allowed are those of an
  // 8-bit BGRA image of max_image_pixels, so an 8-bit image is bounded by its pixels as above.
  // At least a byte: a malformed header may declare no channels (the decoder then refuses it).
  const long long pixel_bytes =
      std::max<long long>(1, static_cast<long long>(header->channels) * header->bytes_per_channel);
  const long long max_bytes = max_pixels > LLONG_MAX / kMaxDecodedBytesPerPixel
                                  ? LLONG_MAX
                                  : max_pixels * kMaxDecodedBytesPerPixel;
  if (header->width > 0 && header->height > max_bytes / (header->width * pixel_bytes))
    throw Error("image '" + name + "' would decode to " +
                std::to_string(header->width * header->height * pixel_bytes) + " bytes (" +
                std::to_string(header->width) + "x" + std::to_string(header->height) +
                " pixels of " + std::to_string(header->channels) + " channels x " +
                std::to_string(header->bytes_per_channel) + " bytes, by its " + header->format +
                " header), more than the " + std::to_string(max_bytes) +
                " bytes allowed (max_image_pixels = " + std::to_string(max_pixels) + " x " +
                std::to_string(kMaxDecodedBytesPerPixel) +
                " bytes, an 8-bit 4-channel image; refused before decoding)");
  // A tiled TIFF is decoded a whole tile at a time, and its header may declare one tile far
  // larger than the image (64 x 64 pixels in one 16384 x 16384 deflate tile: 1.1 GB and 7.5 s
  // for 1.1 MB of file): the tile is bounded as the image is.
  if (header->tile_width > 0 && header->tile_height > max_pixels / header->tile_width)
    throw Error("image '" + name + "' is a TIFF of " + std::to_string(header->tile_width) + "x" +
                std::to_string(header->tile_height) +
                "-pixel tiles (the decoder holds a whole tile at once), more than "
                "max_image_pixels = " +
                std::to_string(max_pixels) + " (refused before decoding)");
  if (header->tile_width > 0 &&
      header->tile_height > max_bytes / (header->tile_width * pixel_bytes))
    throw Error("image '" + name + "' is a TIFF of " + std::to_string(header->tile_width) + "x" +
                std::to_string(header->tile_height) + "-pixel tiles of " +
                std::to_string(pixel_bytes) + " bytes a pixel (the decoder holds a whole tile at " +
                "once), more than the " + std::to_string(max_bytes) +
                " bytes allowed (max_image_pixels = " + std::to_string(max_pixels) + " x " +
                std::to_string(kMaxDecodedBytesPerPixel) + " bytes; refused before decoding)");
  // Each scan of a progressive JPEG is a pass of the decoder over the whole image: a file of
  // 824 KB of repeated scans took 113 s, linear in the scans. Encoders write about ten.
  if (header->scans > kMaxJpegScans)
    throw Error("image '" + name + "' is a JPEG of " + std::to_string(header->scans) +
                " scans, more than the " + std::to_string(kMaxJpegScans) +
                " aief decodes (an encoder writes about ten; so many take minutes to decode; "
                "refused before decoding)");
  // Formats aief does not read (floating-point pixels only; their size is still read, so the
  // limit holds): refused by name before decoding.
  const ImageFormat* format = image_format_named(header->format);
  if (format != nullptr && !format->refusal.empty())
    throw Error("cannot use image '" + name + "': " + std::string(format->refusal) +
                ", which aief does not read (no conversion to 8 bits is right for every use: "
                "tone-map it first)");
}

[[noreturn]] void throw_unreadable(const std::string& name) {
  throw Error("cannot read image '" + name + "': not an image aief can read (" +
              readable_image_format_names() + "; 8- or 16-bit), or its header is damaged");
}

// The same, and an unknown format, for the whole encoded file.
void check_header_before_decoding(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                  long long max_pixels) {
  const std::optional<ImageHeader> header = read_image_header(bytes.data(), bytes.size());
  if (!header) throw_unreadable(name);
  check_header(&*header, name, max_pixels);
}

// A JPEG whose last scan (SOS, FF DA) is not followed by the end-of-image marker (FF D9) was cut
// short. Inside entropy-coded data every FF is followed by 00 or a restart marker, so neither
// marker can appear there by accident.
bool jpeg_is_cut_short(const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return false;
  std::size_t last_scan = 0;
  for (std::size_t i = 2; i + 1 < bytes.size(); ++i)
    if (bytes[i] == 0xFF && bytes[i + 1] == 0xDA) last_scan = i;
  if (last_scan == 0) return false;
  for (std::size_t i = last_scan + 2; i + 1 < bytes.size(); ++i)
    if (bytes[i] == 0xFF && bytes[i + 1] == 0xD9) return false;
  return true;
}

std::string kind_of(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::fifo: return "a FIFO";
    case std::filesystem::file_type::socket: return "a socket";
    case std::filesystem::file_type::character: return "a character device";
    case std::filesystem::file_type::block: return "a block device";
    default: return "unknown kind";
  }
}

}  // namespace

std::vector<std::uint8_t> read_image_file(const std::string& path, long long max_pixels) {
  // Asked before opening: opening a FIFO blocks until a writer comes, maybe forever.
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_type type = fs::status(path, ec).type();
  if (type == fs::file_type::not_found)
    throw Error("cannot open image '" + path + "': no such file");
  if (ec) throw Error("cannot open image '" + path + "': " + ec.message());
  if (type == fs::file_type::directory)
    throw Error("cannot open image '" + path + "': it is a directory");
  if (type != fs::file_type::regular)
    throw Error("cannot open image '" + path + "': not a regular file (" + kind_of(type) +
                "), not opened");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error("cannot open image '" + path + "': permission denied");
  const std::uint64_t size = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
  const ReadAt read_at = [&in](std::uint64_t offset, std::uint8_t* into, std::size_t count) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(into), static_cast<std::streamsize>(count));
    return static_cast<std::size_t>(in.gcount());
  };
  const EncodedBytes file(read_at, size);
  // The header first, from the file's start (a TIFF's first directory from wherever it lies): a
  // size above the limit, or a file of no format aief reads, is refused before the rest is read.
  // Then no more than the image occupies by its header (io/image_extent.hpp), never the file
  // whole first: a 320 x 240 image padded with zeros to 1.5 GB took 1.6 GB and 5-14 s.
  constexpr std::uint64_t kHeaderBytes = 1 << 16;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(std::min(size, kHeaderBytes)));
  if (read_at(0, bytes.data(), bytes.size()) < bytes.size())
    throw Error("cannot read image '" + path + "': read error");
  std::optional<ImageHeader> header = read_image_header(bytes.data(), bytes.size());
  const bool tiff = bytes.size() >= 2 && (std::memcmp(bytes.data(), "II", 2) == 0 ||
                                          std::memcmp(bytes.data(), "MM", 2) == 0);
  if (!header && tiff && size > bytes.size()) header = read_image_header(file);
  if (!header) throw_unreadable(path);
  check_header(&*header, path, max_pixels);
  const std::uint64_t needed = encoded_image_length(*header, file, path);
  const std::size_t start = std::min(bytes.size(), static_cast<std::size_t>(needed));
  bytes.resize(static_cast<std::size_t>(needed));
  if (needed > start && read_at(start, bytes.data() + start, needed - start) < needed - start)
    throw Error("cannot read image '" + path + "': read error");
  return bytes;
}

GrayImage read_gray_image(const std::string& path, long long max_pixels,
                          std::vector<std::string>* warnings) {
  return decode_gray_image(read_image_file(path, max_pixels), path, max_pixels, warnings);
}

GrayImage decode_gray_image(const std::vector<std::uint8_t>& bytes, const std::string& name,
                            long long max_pixels, std::vector<std::string>* warnings) {
  check_header_before_decoding(bytes, name, max_pixels);
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    // The decoder's own message only, not OpenCV's source location and assertion text.
    throw Error("cannot read image '" + name + "': the decoder failed (" + e.err + ")");
  }
  if (image.empty())
    throw Error("cannot read image '" + name +
                "': not an image OpenCV can decode, or a damaged file");
  if (warnings && jpeg_is_cut_short(bytes))
    warnings->push_back("image '" + name +
                        "': the JPEG data ends before its end-of-image marker (a file cut short): "
                        "the decoder filled "
                        "the missing part with grey");
  return gray_from_decoded(image, name);
}

GrayImage gray_from_pixels(const std::uint8_t* pixels, int width, int height, int channels,
                           std::ptrdiff_t row_stride, const std::string& name) {
  if (width <= 0 || height <= 0 || pixels == nullptr)
    throw Error("cannot use image '" + name + "': it is empty (" + std::to_string(width) + "x" +
                std::to_string(height) + ")");
  if (channels != 1 && channels != 3 && channels != 4)
    throw Error("cannot use image '" + name + "': " + std::to_string(channels) +
                " channels (expected 1, 3 or 4)");
  // A header over the caller's bytes (OpenCV does not write through it): the conversion is the
  // one read_gray_image applies to a decoded file.
  const cv::Mat image(height, width, CV_8UC(channels), const_cast<std::uint8_t*>(pixels),
                      static_cast<std::size_t>(row_stride));
  return gray_from_decoded(image, name);
}

}  // namespace aief::io

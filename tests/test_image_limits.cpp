// Image reading within limits: each format's header read before decoding (io/image_header.hpp),
// and what would take too much memory or time refused before the decoder runs: too many pixels or
// decoded bytes, a JPEG of too many scans, a TIFF tile too large, a file read no further than its
// format needs.
#include <filesystem>
#include <fstream>
#include <optional>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/image_header.hpp"
#include "io/image_io.hpp"
#include "tests/io_test_support.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using TempDir = test::TempFolder;
using test::bytes_of;
using test::error_of;

TEST(ImageHeader, ReadsTheSizeEveryFormatDeclaresAndSurvivesEveryCut) {
  // OpenCV's encoders are the oracle: what they write at 37 x 33, the parser reads back.
  const cv::Mat gray = test::random_image(37, 33, 5);
  cv::Mat colour;
  cv::cvtColor(gray, colour, cv::COLOR_GRAY2BGR);
  cv::Mat real;
  colour.convertTo(real, CV_32FC3, 1.0 / 255.0);
  struct Case {
    const char* extension;
    const cv::Mat* image;
    std::vector<int> params;
  };
  const Case cases[] = {{".png", &gray, {}},
                        {".png", &colour, {}},
                        {".jpg", &gray, {}},
                        {".jpg", &colour, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}},
                        {".tiff", &gray, {}},
                        {".webp", &colour, {}},
                        {".webp", &colour, {cv::IMWRITE_WEBP_QUALITY, 101}},
                        {".bmp", &gray, {}},
                        {".bmp", &colour, {}},
                        {".pgm", &gray, {}},
                        {".pgm", &gray, {cv::IMWRITE_PXM_BINARY, 0}},
                        {".ppm", &colour, {}},
                        {".pbm", &gray, {}},
                        {".pam", &gray, {}},
                        {".sr", &gray, {}},
                        {".pfm", &real, {}},
                        {".hdr", &real, {}},
                        {".jp2", &colour, {}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.extension);
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(cv::imencode(c.extension, *c.image, bytes, c.params));
    const std::optional<io::ImageHeader> header = io::read_image_header(bytes.data(), bytes.size());
    ASSERT_TRUE(header.has_value());
    EXPECT_EQ(header->width, 37);
    EXPECT_EQ(header->height, 33);
    for (std::size_t cut = 0; cut < std::min<std::size_t>(bytes.size(), 200); ++cut)
      io::read_image_header(bytes.data(), cut);
  }
  const std::vector<std::uint8_t> bomb = test::png_declaring(30000, 30000);
  const std::optional<io::ImageHeader> header = io::read_image_header(bomb.data(), bomb.size());
  ASSERT_TRUE(header.has_value());
  EXPECT_EQ(header->width, 30000);
  EXPECT_EQ(header->format, "PNG");
  EXPECT_FALSE(
      io::read_image_header(reinterpret_cast<const std::uint8_t*>("GIF89a"), 6).has_value());
}

TEST(ImageIo, RefusesMorePixelsThanAllowedBeforeDecoding) {
  TempDir dir;
  // A 900 KB-class bomb in miniature: a valid PNG whose header declares 30000 x 30000 (and one
  // at 65535 x 65535, which OpenCV itself would refuse with its assertion text).
  for (const std::uint32_t side : {30000u, 65535u}) {
    const std::vector<std::uint8_t> bomb = test::png_declaring(side, side);
    std::ofstream(dir.file("bomb.png"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bomb.data()),
               static_cast<std::streamsize>(bomb.size()));
    const std::string message = error_of(dir.file("bomb.png"));
    const std::string size = std::to_string(side) + "x" + std::to_string(side);
    EXPECT_NE(message.find("declares " + size), std::string::npos) << message;
    EXPECT_NE(message.find("refused before decoding"), std::string::npos) << message;
    EXPECT_EQ(message.find("OpenCV"), std::string::npos) << message;
  }
  // The limit is exact, in every format: w x h pixels pass at w x h, and are refused one below.
  const cv::Mat gray = test::random_image(41, 33, 6);
  for (const char* extension :
       {".png", ".jpg", ".tiff", ".webp", ".bmp", ".pgm", ".pam", ".sr", ".jp2"}) {
    SCOPED_TRACE(extension);
    const std::string path = dir.file(std::string("small") + extension);
    ASSERT_TRUE(cv::imwrite(path, gray));
    EXPECT_EQ(io::read_gray_image(path, 41 * 33).width(), 41);
    try {
      io::read_gray_image(path, 41 * 33 - 1);
      ADD_FAILURE() << "not refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("refused before decoding"), std::string::npos)
          << e.what();
    }
    EXPECT_THROW(io::decode_gray_image(bytes_of(path), path, 41 * 33 - 1), Error);
  }
  // A format whose size cannot be read first is refused, not decoded blind.
  std::ofstream(dir.file("x.gif")) << "GIF89a\x10\x00\x10\x00";
  EXPECT_NE(error_of(dir.file("x.gif")).find("not an image aief can read"), std::string::npos);
}

// The guard counts the bytes the decoder allocates, not pixels: a 16-bit RGBA PNG (8 bytes a
// pixel) at the pixel limit is refused, naming the limit; the header gives each format's layout.
// Was: only pixels counted (a 522 KB 16-bit RGBA PNG decoded to 0.9 GB).
TEST(ImageIo, RefusesMoreDecodedBytesThanAllowedBeforeDecoding) {
  TempDir dir;
  const cv::Mat gray = test::random_image(41, 33, 7);
  cv::Mat bgra, bgra16, bgr16, gray16;
  cv::cvtColor(gray, bgra, cv::COLOR_GRAY2BGRA);
  bgra.convertTo(bgra16, CV_16UC4, 257);
  cv::cvtColor(bgra16, bgr16, cv::COLOR_BGRA2BGR);
  gray.convertTo(gray16, CV_16U, 257);
  struct Case {
    const char* extension;
    const cv::Mat* image;
    int channels, bytes_per_channel;
  };
  for (const Case& c :
       {Case{".png", &bgra16, 4, 2}, Case{".png", &gray, 1, 1}, Case{".png", &bgra, 4, 1},
        Case{".pgm", &gray16, 1, 2}, Case{".ppm", &bgr16, 3, 2}, Case{".tiff", &bgr16, 3, 2},
        Case{".tiff", &gray, 1, 1}, Case{".pam", &gray, 1, 1}, Case{".jpg", &gray, 1, 1},
        Case{".jp2", &bgr16, 3, 2}}) {
    SCOPED_TRACE(std::string(c.extension) + " " + std::to_string(c.image->channels()));
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(cv::imencode(c.extension, *c.image, bytes));
    const std::optional<io::ImageHeader> header = io::read_image_header(bytes.data(), bytes.size());
    ASSERT_TRUE(header.has_value());
    EXPECT_EQ(header->channels, c.channels);
    EXPECT_EQ(header->bytes_per_channel, c.bytes_per_channel);
  }
  const std::string path = dir.file("deep.png");
  ASSERT_TRUE(cv::imwrite(path, bgra16));
  const long long pixels = 41 * 33;
  try {
    io::read_gray_image(path, pixels);
    ADD_FAILURE() << "a 16-bit RGBA PNG at the pixel limit was decoded";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("would decode to " + std::to_string(pixels * 8) + " bytes"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(std::to_string(pixels * 4) +
                           " bytes allowed (max_image_pixels = " + std::to_string(pixels)),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(io::read_gray_image(path, pixels * 2).width(), 41);  // 8 bytes a pixel fit
  ASSERT_TRUE(cv::imwrite(dir.file("bgra.png"), bgra));
  EXPECT_EQ(io::read_gray_image(dir.file("bgra.png"), pixels).width(), 41);  // as before
}

// A progressive JPEG's scans are counted from its bytes before decoding: more than 500 (each a
// pass of the decoder over the image) is refused; an encoder's ten are read. Was: 113 s for a
// file of 824 KB of repeated scans.
TEST(ImageIo, AJpegOfTooManyScansIsRefusedBeforeDecoding) {
  TempDir dir;
  const cv::Mat colour = cv::imread(test::sample_path("boat", "img1.png"));
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(cv::imencode(".jpg", colour, bytes, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  const std::optional<io::ImageHeader> header = io::read_image_header(bytes.data(), bytes.size());
  ASSERT_TRUE(header.has_value());
  EXPECT_GT(header->scans, 1);
  EXPECT_LE(header->scans, 20);
  EXPECT_EQ(io::decode_gray_image(bytes, "progressive.jpg").width(), colour.cols);
  // The last scan (its SOS segment and data, up to the end-of-image marker) repeated.
  std::size_t last_scan = 0;
  for (std::size_t i = 2; i + 1 < bytes.size(); ++i)
    if (bytes[i] == 0xFF && bytes[i + 1] == 0xDA) last_scan = i;
  ASSERT_GT(last_scan, 0u);
  const std::vector<std::uint8_t> scan(bytes.begin() + static_cast<std::ptrdiff_t>(last_scan),
                                       bytes.end() - 2);
  std::vector<std::uint8_t> many(bytes.begin(), bytes.end() - 2);
  for (int copy = 0; copy < 600; ++copy) many.insert(many.end(), scan.begin(), scan.end());
  many.insert(many.end(), {0xFF, 0xD9});
  std::ofstream(dir.file("scans.jpg"), std::ios::binary)
      .write(reinterpret_cast<const char*>(many.data()), static_cast<std::streamsize>(many.size()));
  const std::string message = error_of(dir.file("scans.jpg"));
  EXPECT_NE(message.find("is a JPEG of " + std::to_string(header->scans + 600) + " scans"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("more than the 500"), std::string::npos) << message;
}

// A little-endian TIFF header: `width` x `height` 8-bit gray, deflate, one tile of `tile` x `tile`
// pixels (its data a few bytes: nothing reaches the decoder).
std::vector<std::uint8_t> tiff_of_one_tile(std::uint32_t width, std::uint32_t height,
                                           std::uint32_t tile) {
  std::vector<std::uint8_t> b = {'I', 'I', 42, 0, 8, 0, 0, 0};
  const auto u16 = [&](std::uint32_t v) {
    b.push_back(static_cast<std::uint8_t>(v));
    b.push_back(static_cast<std::uint8_t>(v >> 8));
  };
  const auto u32 = [&](std::uint32_t v) {
    u16(v & 0xFFFF);
    u16(v >> 16);
  };
  const std::uint32_t entries = 10, data = 8 + 2 + entries * 12 + 4;
  u16(entries);
  const auto entry = [&](std::uint32_t tag, std::uint32_t type, std::uint32_t value) {
    u16(tag);
    u16(type);
    u32(1);
    u32(value);
  };
  entry(256, 4, width);
  entry(257, 4, height);
  entry(258, 3, 8);     // BitsPerSample
  entry(259, 3, 8);     // Compression: deflate
  entry(262, 3, 1);     // Photometric: black is zero
  entry(277, 3, 1);     // SamplesPerPixel
  entry(284, 3, 1);     // PlanarConfiguration: contiguous
  entry(322, 4, tile);  // TileWidth
  entry(323, 4, tile);  // TileLength
  entry(324, 4, data);  // TileOffsets (TileByteCounts left out: the header is refused first)
  u32(0);               // no next IFD
  for (int i = 0; i < 16; ++i) b.push_back(0);
  return b;
}

// A TIFF of 64 x 64 pixels in one 16384 x 16384 deflate tile (1.1 MB) took 7.5 s and 1.11 GB, also
// with --max-image-pixels 5000: the decoder holds a whole tile. The tile is bounded as the image.
TEST(ImageIo, ATiffTileLargerThanAllowedIsRefusedBeforeDecoding) {
  TempDir dir;
  const std::vector<std::uint8_t> bomb = tiff_of_one_tile(64, 64, 16384);
  const std::optional<io::ImageHeader> header = io::read_image_header(bomb.data(), bomb.size());
  ASSERT_TRUE(header.has_value());
  EXPECT_EQ(header->width, 64);
  EXPECT_EQ(header->tile_width, 16384);
  EXPECT_EQ(header->tile_height, 16384);
  std::ofstream(dir.file("tile.tiff"), std::ios::binary)
      .write(reinterpret_cast<const char*>(bomb.data()), static_cast<std::streamsize>(bomb.size()));
  for (const long long limit : {ExtractorOptions{}.max_image_pixels, 5000LL}) {
    try {
      io::read_gray_image(dir.file("tile.tiff"), limit);
      ADD_FAILURE() << "not refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("is a TIFF of 16384x16384-pixel tiles"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("refused before decoding"), std::string::npos);
    }
  }
  // Tiles within the limit are read as before: OpenCV's own tiled TIFF (256 x 256 tiles).
  const cv::Mat gray = test::random_image(300, 200, 3);
  const std::optional<io::ImageHeader> small = io::read_image_header(
      tiff_of_one_tile(300, 200, 256).data(), tiff_of_one_tile(300, 200, 256).size());
  ASSERT_TRUE(small.has_value());
  EXPECT_EQ(small->tile_width, 256);
  ASSERT_TRUE(cv::imwrite(dir.file("strips.tiff"), gray));
  EXPECT_EQ(io::read_gray_image(dir.file("strips.tiff"), 300 * 200).width(), 300);
}

// Bytes this process has read through read() so far (/proc/self/io's rchar).
long long bytes_read_so_far() {
  std::ifstream io("/proc/self/io");
  std::string key;
  long long value = 0;
  while (io >> key >> value)
    if (key == "rchar:") return value;
  return -1;
}

// A 320 x 240 PNG padded to 1.5 GB was read whole before its header was checked (25 s, 1.6 GB).
// Now the header is read first and a PNG no further than its IEND chunk. The padding here is a
// hole of a sparse file (64 MB that cost no disk), and what was read is counted by the kernel.
TEST(ImageIo, AFileIsReadNoFurtherThanItsFormatNeeds) {
  TempDir dir;
  if (bytes_read_so_far() < 0) GTEST_SKIP() << "no /proc/self/io here";
  constexpr std::uintmax_t kPadding = 64u << 20;
  const std::string padded = dir.file("padded.png");
  ASSERT_TRUE(cv::imwrite(padded, test::random_image(320, 240, 5)));
  std::filesystem::resize_file(padded, std::filesystem::file_size(padded) + kPadding);
  long long before = bytes_read_so_far();
  EXPECT_EQ(io::read_gray_image(padded).width(), 320);
  EXPECT_LT(bytes_read_so_far() - before, 4 << 20);
  // A bomb's header is refused before the rest of the file is read.
  const std::vector<std::uint8_t> bomb = test::png_declaring(30000, 30000);
  const std::string bomb_path = dir.file("bomb.png");
  std::ofstream(bomb_path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bomb.data()), static_cast<std::streamsize>(bomb.size()));
  std::filesystem::resize_file(bomb_path, bomb.size() + kPadding);
  before = bytes_read_so_far();
  EXPECT_NE(error_of(bomb_path).find("refused before decoding"), std::string::npos);
  EXPECT_LT(bytes_read_so_far() - before, 1 << 20);
}

// JPEG, WebP, BMP, TIFF and PNM padded to 1.5 GB were read whole before decoding (5-14 s and
// 1.6 GB each); now each is read no further than its header says the image occupies, and the
// decoder is handed exactly the bytes written.
TEST(ImageIo, EveryFormatIsReadNoFurtherThanItsHeaderSays) {
  TempDir dir;
  if (bytes_read_so_far() < 0) GTEST_SKIP() << "no /proc/self/io here";
  constexpr std::uintmax_t kPadding = 64u << 20;
  const cv::Mat gray = test::random_image(320, 240, 7);
  cv::Mat colour;
  cv::cvtColor(gray, colour, cv::COLOR_GRAY2BGR);
  const std::vector<std::pair<std::string, std::vector<int>>> files = {
      {"a.jpg", {}},
      {"a.webp", {}},
      {"a.bmp", {}},
      {"a.tiff", {}},
      {"a.ppm", {}},
      {"a.pgm", {}},
      {"plain.pgm", {cv::IMWRITE_PXM_BINARY, 0}},
      {"a.pbm", {}},
      {"a.pam", {}}};
  for (const auto& [name, parameters] : files) {
    SCOPED_TRACE(name);
    const std::string path = dir.file(name);
    ASSERT_TRUE(
        cv::imwrite(path, name.find("ppm") != std::string::npos ? colour : gray, parameters));
    const std::uintmax_t written = std::filesystem::file_size(path);
    const GrayImage unpadded = io::read_gray_image(path);
    std::filesystem::resize_file(path, written + kPadding);
    const long long before = bytes_read_so_far();
    EXPECT_EQ(io::read_image_file(path).size(), written);
    EXPECT_LT(bytes_read_so_far() - before, 4 << 20);
    const GrayImage padded = io::read_gray_image(path);
    ASSERT_EQ(padded.width(), unpadded.width());
    EXPECT_TRUE(std::equal(padded.data(), padded.data() + padded.width() * padded.height(),
                           unpadded.data()));
  }
  // A file of no format aief reads is refused from its first bytes, not read whole first.
  const std::string zeros = dir.file("zeros.png");
  std::ofstream(zeros, std::ios::binary).put('\0');
  std::filesystem::resize_file(zeros, kPadding);
  const long long before = bytes_read_so_far();
  EXPECT_NE(error_of(zeros).find("not an image aief can read"), std::string::npos);
  EXPECT_LT(bytes_read_so_far() - before, 1 << 20);
}

// A 16 x 16 TIFF of one row a strip whose strip arrays declare 4 M entries, in a file padded with
// zeros: the extent took every entry's array (16 MB each; 300 M entries in a file of 1.5 GB read
// 1.2 GB in 14 s). libtiff reads as many strips as the image has (16): so does the extent.
TEST(ImageIo, ATiffIsReadToTheStripsItsSizeMakesNotToTheCountItsArraysDeclare) {
  TempDir dir;
  constexpr std::uint32_t kDeclared = 4u << 20, kArrays = 4096;
  std::vector<std::uint8_t> tiff = {'I', 'I', 42, 0, 8, 0, 0, 0};
  const auto put = [&tiff](std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) tiff.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  };
  // Tag, type (3 SHORT, 4 LONG), count, value (or where the values are).
  const std::uint32_t entries[][4] = {
      {256, 3, 1, 16}, {257, 3, 1, 16}, {258, 3, 1, 8},
      {259, 3, 1, 1},  {262, 3, 1, 1},  {273, 4, kDeclared, kArrays},
      {277, 3, 1, 1},  {278, 3, 1, 1},  {279, 4, kDeclared, kArrays}};
  put(std::size(entries), 2);
  for (const auto& [tag, type, count, value] : entries) {
    put(tag, 2);
    put(type, 2);
    put(count, 4);
    put(value, 4);
  }
  put(0, 4);  // no next directory
  const std::string path = dir.file("strips.tiff");
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(tiff.data()), static_cast<std::streamsize>(tiff.size()));
  std::filesystem::resize_file(path, 64u << 20);
  // Its strips (zeros: at offset 0, of 0 bytes) end where the directory does; the arrays' first
  // 16 entries after it.
  EXPECT_EQ(io::read_image_file(path).size(), kArrays + 16 * 4);
}

// A PNG without its IEND chunk, padded with zeros to 1.5 GB: the chunk walk went on through the
// padding 12 bytes a step (more than 120 s), then read the file whole. The first chunk that
// cannot be (type 00 00 00 00) ends the walk, and the file is refused naming where.
TEST(ImageIo, APngWhoseChunksRunIntoPaddingIsRefusedAtTheFirstImpossibleChunk) {
  TempDir dir;
  if (bytes_read_so_far() < 0) GTEST_SKIP() << "no /proc/self/io here";
  std::vector<std::uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", test::random_image(320, 240, 9), png));
  png.resize(png.size() - 12);  // IEND dropped
  const std::string path = dir.file("no_end.png");
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  std::filesystem::resize_file(path, png.size() + (64u << 20));
  const long long before = bytes_read_so_far();
  const std::string message = error_of(path);
  EXPECT_NE(message.find("its PNG chunks end at byte " + std::to_string(png.size()) +
                         " before any IEND chunk"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("type 00 00 00 00"), std::string::npos) << message;
  EXPECT_LT(bytes_read_so_far() - before, 4 << 20);
}

}  // namespace
}  // namespace aief

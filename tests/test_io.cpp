// Image reading (conversions, clear errors) and result files (JSON, OpenCV YAML read back).
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/feature_formats.hpp"
#include "io/image_header.hpp"
#include "io/image_io.hpp"
#include "io/npz_writer.hpp"
#include "tests/odd_names.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using TempDir = test::TempFolder;

std::string error_of(const std::string& path) {
  try {
    io::read_gray_image(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImageIo, ReadsGrayAndConvertsColourDepthAndAlpha) {
  TempDir dir;
  cv::Mat colour(20, 30, CV_8UC3);
  cv::randu(colour, 0, 255);
  cv::imwrite(dir.file("c.png"), colour);
  cv::Mat expected;
  cv::cvtColor(colour, expected, cv::COLOR_BGR2GRAY);
  GrayImage gray = io::read_gray_image(dir.file("c.png"));
  ASSERT_EQ(gray.width(), 30);
  ASSERT_EQ(gray.height(), 20);
  EXPECT_EQ(0, std::memcmp(gray.data(), expected.data, 600));
  // Not what the decoder's own gray conversion gives (docs/command_line.md, "Colour to gray"):
  // libpng truncates.
  const cv::Mat decoder_gray = cv::imread(dir.file("c.png"), cv::IMREAD_GRAYSCALE);
  EXPECT_NE(0, std::memcmp(gray.data(), decoder_gray.data, 600));

  cv::Mat rgba(10, 12, CV_8UC4, cv::Scalar(10, 20, 30, 0));
  cv::imwrite(dir.file("a.png"), rgba);
  EXPECT_EQ(io::read_gray_image(dir.file("a.png")).width(), 12);

  cv::Mat real(8, 9, CV_32FC1, cv::Scalar(0.5));  // float images are refused with the depth named
  cv::imwrite(dir.file("f.tiff"), real);
  EXPECT_NE(
      error_of(dir.file("f.tiff")).find("its pixels are 32-bit float, not 8- or 16-bit unsigned"),
      std::string::npos)
      << error_of(dir.file("f.tiff"));
  // Formats of float pixels only: refused by name, before decoding, never listed as readable.
  cv::Mat radiance(8, 9, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
  cv::imwrite(dir.file("r.hdr"), radiance);
  EXPECT_NE(error_of(dir.file("r.hdr")).find("a Radiance HDR file holds floating-point pixels"),
            std::string::npos)
      << error_of(dir.file("r.hdr"));
  std::ofstream(dir.file("p.pfm"), std::ios::binary) << "Pf\n9 8\n-1.0\n"
                                                     << std::string(9 * 8 * 4, '\0');
  EXPECT_NE(error_of(dir.file("p.pfm")).find("a PFM file holds floating-point pixels"),
            std::string::npos)
      << error_of(dir.file("p.pfm"));
  std::ofstream(dir.file("unknown.png")) << "GIF89a";
  EXPECT_EQ(error_of(dir.file("unknown.png")).find("HDR"), std::string::npos)
      << "listed as readable";
  EXPECT_EQ(error_of(dir.file("unknown.png")).find("PFM"), std::string::npos)
      << "listed as readable";

  cv::Mat deep(8, 9, CV_16UC1, cv::Scalar(51200));  // 200 * 256
  cv::imwrite(dir.file("d.png"), deep);
  const GrayImage eight = io::read_gray_image(dir.file("d.png"));
  EXPECT_EQ(eight.data()[0], 200);
}

TEST(ImageIo, AFifoIsRefusedWithoutOpeningIt) {
  TempDir dir;
  const std::string fifo = dir.file("fifo.png");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // Opening it would wait for a writer: if the read has not answered in a minute, a writer ends
  // the wait so that the test fails instead of hanging.
  std::future<std::string> refusal = std::async(std::launch::async, [&] { return error_of(fifo); });
  if (refusal.wait_for(std::chrono::seconds(60)) != std::future_status::ready) {
    ADD_FAILURE() << "reading a FIFO blocked";
    std::ofstream(fifo) << "x";
  }
  EXPECT_NE(refusal.get().find("not a regular file (a FIFO), not opened"), std::string::npos);
}

TEST(ImageIo, ClearErrorsForBadFiles) {
  TempDir dir;
  EXPECT_NE(error_of(dir.file("missing.png")).find("no such file"), std::string::npos);
  EXPECT_NE(error_of(dir.path().string()).find("directory"), std::string::npos);
  std::ofstream(dir.file("text.png")) << "this is not an image";
  EXPECT_NE(error_of(dir.file("text.png")).find("cannot read image"), std::string::npos);
  // Truncated PNG and JPEG: the first part of a valid file.
  for (const char* ext : {".png", ".jpg"}) {
    std::vector<std::uint8_t> bytes;
    cv::imencode(ext, test::random_image(64, 64, 3), bytes);
    std::ofstream out(dir.file(std::string("cut") + ext), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size() / 3));
    out.close();
    std::string message;
    try {
      const GrayImage image = io::read_gray_image(dir.file(std::string("cut") + ext));
      message = "decoded " +
                std::to_string(image.width());  // libjpeg pads a cut file: an image, no crash
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_FALSE(message.empty()) << ext;
  }
}

std::vector<std::uint8_t> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
}

// OpenCV hands bytes carrying DICOM's signature ("DICM" at offset 128) to GDCM before its JPEG 2000
// decoders, and GDCM aborts the process on a damaged file (the fuzzer's finding, kept in
// fuzz/corpus/image_bytes/regression_dicom_signature): such bytes are refused before decoding.
TEST(ImageIo, BytesOpenCvWouldHandToItsDicomDecoderAreRefused) {
  std::vector<std::uint8_t> jpeg2000;
  ASSERT_TRUE(cv::imencode(".jp2", test::random_image(64, 64, 1), jpeg2000));
  ASSERT_GT(jpeg2000.size(), 132u);
  EXPECT_EQ(io::decode_gray_image(jpeg2000, "plain.jp2").width(), 64);
  std::memcpy(jpeg2000.data() + 128, "DICM", 4);
  try {
    io::decode_gray_image(jpeg2000, "dicom_signature.jp2");
    ADD_FAILURE() << "decoded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an image aief can read"), std::string::npos)
        << e.what();
  }
  const std::string finding =
      std::string(AIEF_DATA_DIR) + "/../fuzz/corpus/image_bytes/regression_dicom_signature";
  EXPECT_THROW(io::decode_gray_image(bytes_of(finding), finding), Error);
}


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

TEST(ImageIo, AJpegCutShortIsDecodedWithAWarning) {
  TempDir dir;
  const cv::Mat colour = cv::imread(test::sample_path("boat", "img1.png"));
  std::vector<std::string> warnings;
  for (const int progressive : {0, 1}) {  // whole files, several scans or one: no warning
    std::vector<std::uint8_t> bytes;
    cv::imencode(".jpg", colour, bytes, {cv::IMWRITE_JPEG_PROGRESSIVE, progressive});
    io::decode_gray_image(bytes, "whole.jpg", ExtractorOptions{}.max_image_pixels, &warnings);
  }
  EXPECT_TRUE(warnings.empty());
  // Cut in half: libjpeg still gives an image (OpenCV refuses a cut progressive one outright).
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", colour, bytes);
  bytes.resize(bytes.size() / 2);
  std::ofstream(dir.file("cut.jpg"), std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  const GrayImage image =
      io::read_gray_image(dir.file("cut.jpg"), ExtractorOptions{}.max_image_pixels, &warnings);
  EXPECT_EQ(image.width(), colour.cols);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("cut short"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("cut.jpg"), std::string::npos) << warnings[0];
}

TEST(FeatureFiles, JsonAndYamlCarryEveryKeypointAndDescriptor) {
  TempDir dir;
  const cv::Mat gray = test::load_sample_gray("boat", "img1.png");
  ExtractorOptions options;
  options.n_features = 200;
  const Features features = extract(view_of(gray), options);
  ASSERT_GT(features.keypoints.size(), 100u);

  io::write_features(dir.file("f.json"), "boat.png", features, options);
  std::ifstream in(dir.file("f.json"));
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"image\":\"boat.png\""), std::string::npos);
  EXPECT_NE(json.find("\"width\":850"), std::string::npos);
  EXPECT_NE(json.find("\"n_features\":200"), std::string::npos);
  std::size_t hex_strings = 0, keypoints = 0;
  for (std::size_t at = json.find("\"octave\""); at != std::string::npos;
       at = json.find("\"octave\"", at + 1))
    ++keypoints;
  const std::size_t list = json.find("\"descriptors_hex\"");
  for (std::size_t at = json.find('"', list + 18); at != std::string::npos;
       at = json.find('"', at + 66)) {
    ASSERT_EQ(json[at + 65], '"') << "descriptor string of 64 hex characters";
    ++hex_strings;
  }
  EXPECT_EQ(keypoints, features.keypoints.size());
  EXPECT_EQ(hex_strings, features.descriptors.size());
  EXPECT_FALSE(std::filesystem::exists(dir.file("f.json.tmp")));

  io::write_features(dir.file("f.yml"), "boat.png", features, options);
  cv::FileStorage fs(dir.file("f.yml"), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  std::vector<cv::KeyPoint> keypoints_back;
  cv::read(fs["keypoints"], keypoints_back);
  cv::Mat descriptors;
  fs["descriptors"] >> descriptors;
  ASSERT_EQ(keypoints_back.size(), features.keypoints.size());
  ASSERT_EQ(descriptors.rows, static_cast<int>(features.descriptors.size()));
  ASSERT_EQ(descriptors.cols, 32);
  ASSERT_EQ(descriptors.type(), CV_8U);
  for (std::size_t i = 0; i < keypoints_back.size(); ++i) {
    EXPECT_EQ(keypoints_back[i].pt.x, features.keypoints[i].x);
    EXPECT_EQ(keypoints_back[i].octave, features.keypoints[i].octave);
    EXPECT_EQ(
        0, std::memcmp(descriptors.ptr(static_cast<int>(i)), features.descriptors[i].data(), 32));
  }
  EXPECT_THROW(io::write_features(dir.file("f.txt"), "x", features, options), Error);
}

TEST(FeatureFiles, YamlRoundTripsEveryOddNameAndRefusesControlCharactersClearly) {
  TempDir dir;
  const GrayImage image = io::read_gray_image(test::sample_path("boat", "img1.png"));
  ExtractorOptions options;
  options.n_features = 50;
  const Features features = extract(image.view(), options);
  int file = 0;
  for (const std::string& name : test::odd_image_names()) {
    io::SourceRecord source{name, 1234, 5678, {}};
    for (const char* extension : {".yml", ".json", ".npz"}) {
      const std::string path = dir.file(std::to_string(file++) + extension);
      ASSERT_NO_THROW(io::write_features(path, name, features, options, source)) << name;
      EXPECT_TRUE(io::features_file_belongs_to(path, source))
          << extension << " '" << name << "' read back as another name";
      source.bytes += 1;
      EXPECT_FALSE(io::features_file_belongs_to(path, source)) << name;
      source.bytes -= 1;
      if (std::string(extension) != ".yml") continue;
      cv::FileStorage fs(path, cv::FileStorage::READ);
      ASSERT_TRUE(fs.isOpened()) << name;
      EXPECT_EQ(static_cast<std::string>(fs["image"]), name);
      EXPECT_EQ(static_cast<std::string>(fs["source_name"]), name);
      cv::Mat descriptors;
      fs["descriptors"] >> descriptors;
      EXPECT_EQ(descriptors.rows, static_cast<int>(features.descriptors.size())) << name;
    }
  }
  for (const std::string& name : test::control_character_names()) {
    const io::SourceRecord source{name, 1, 2, {}};
    try {
      io::write_features(dir.file("control.yml"), name, features, options, source);
      ADD_FAILURE() << "YAML accepted a name it cannot read back";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("YAML cannot hold the image name"), std::string::npos)
          << e.what();
      // The formats that can, from the registry's rows (io/feature_formats.cpp).
      EXPECT_NE(std::string(e.what()).find("(write .json or .npz for such names)"),
                std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("control.yml")));
    io::write_features(dir.file("control.json"), name, features, options, source);
    EXPECT_TRUE(io::features_file_belongs_to(dir.file("control.json"), source));
  }
  // Longer than OpenCV's YAML strings (4094 bytes), escapes counted: refused, not cut.
  const std::string long_name = std::string(2100, 'a') + std::string(1000, '"') + ".png";
  EXPECT_THROW(io::write_features(dir.file("long.yml"), long_name, features, options,
                                  io::SourceRecord{long_name, 1, 2, {}}),
               Error);
}

}  // namespace
}  // namespace aief

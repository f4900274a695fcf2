// Image reading: conversions of colour, depth and alpha to 8-bit gray, clear errors for what is
// no image aief reads, a JPEG cut short (the limits on what is decoded:
// tests/test_image_limits.cpp).
#include <chrono>
#include <cstring>
#include <fstream>
#include <future>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/image_io.hpp"
#include "tests/io_test_support.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

using TempDir = test::TempFolder;
using test::bytes_of;
using test::error_of;

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

}  // namespace
}  // namespace aief

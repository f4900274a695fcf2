#pragma once
// Image files in: anything OpenCV's imgcodecs reads, as 8-bit gray.
//
// Conversion: 3- and 4-channel images -> gray by OpenCV's cvtColor (ITU-R BT.601 luma,
// 0.299 R + 0.587 G + 0.114 B, OpenCV's fixed point); 16-bit images -> 8 bits, divided by 256
// and rounded; other depths (float, signed) are refused naming the depth in words ("32-bit
// float"), and Radiance HDR and PFM, formats of float pixels only, by name before decoding. A
// path that is not a regular file (a FIFO, a device) is refused before it is opened (opening a
// FIFO waits for a writer). Errors are aief::Error naming the path.
//
// Size first: the width and height the file declares are read from its header (io/image_header.hpp)
// and a file above `max_pixels` (ExtractorOptions::max_image_pixels) is refused before anything
// is decoded or allocated; a file whose size cannot be read from its header is refused too.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "aief/image.hpp"
#include "aief/options.hpp"

namespace aief::io {

// The bytes of the image file at `path` that the decoder is handed: its header is read and
// checked first (the checks above), then only what the image occupies by that header
// (io/image_extent.hpp: a PNG to its IEND, a JPEG to its end-of-image marker, ...), never the
// file whole first: padding after the image is not read. Throws aief::Error.
std::vector<std::uint8_t> read_image_file(
    const std::string& path, long long max_pixels = ExtractorOptions{}.max_image_pixels);

// read_image_file's bytes, decoded.
//
// Warnings: a file the decoder still turns into an image but not the whole of it (a JPEG cut short
// before its end-of-image marker: libjpeg fills the rest with grey) adds a sentence to `warnings`
// when given. Damaged data inside a JPEG scan is not detected (it would take a second decode).
GrayImage read_gray_image(const std::string& path,
                          long long max_pixels = ExtractorOptions{}.max_image_pixels,
                          std::vector<std::string>* warnings = nullptr);

// The same conversion for an image already in memory as encoded bytes (PNG, JPEG, ...);
// `name` goes into the error messages.
GrayImage decode_gray_image(const std::vector<std::uint8_t>& bytes, const std::string& name,
                            long long max_pixels = ExtractorOptions{}.max_image_pixels,
                            std::vector<std::string>* warnings = nullptr);

// The same conversion for 8-bit pixels already in memory (the Python module's BGR / BGRA
// arrays): `channels` (1, 3 BGR or 4 BGRA) interleaved bytes per pixel, consecutive within a
// row, rows `row_stride` bytes apart. `name` goes into the error messages.
GrayImage gray_from_pixels(const std::uint8_t* pixels, int width, int height, int channels,
                           std::ptrdiff_t row_stride, const std::string& name);

}  // namespace aief::io

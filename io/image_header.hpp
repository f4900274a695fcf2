#pragma once
// The size an encoded image declares, read from its header alone: nothing is decoded or
// allocated, so a 1 MB PNG declaring 30000 x 30000 pixels is refused before the decoder would
// ask for gigabytes. OpenCV 4.6 has no header-only API (cv::imdecode allocates the full image),
// hence this parser of the formats its imgcodecs reads here: PNG (IHDR), JPEG (SOFn), TIFF and
// BigTIFF (first IFD's ImageWidth / ImageLength, and TileWidth / TileLength), WebP (VP8, VP8L,
// VP8X), BMP, PNM / PAM / PFM, Sun raster, Radiance HDR, JPEG 2000 (JP2 ihdr box, J2K SIZ marker).
// Besides the size: the decoded pixel layout where the header gives it (PNG, JPEG, TIFF, PNM, PAM,
// JPEG 2000), and a JPEG's number of scans, so that what decoding would cost is known before it
// starts.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "io/encoded_bytes.hpp"

namespace aief::io {

struct ImageHeader {
  std::string format;  // "PNG", "JPEG", ...
  long long width = 0, height = 0;
  // A pixel as OpenCV decodes it (imdecode, IMREAD_UNCHANGED): channels of bytes_per_channel
  // each (2 for 16-bit samples). Where the header does not say: 4 of 1, the most an 8-bit format
  // decodes to (BGRA).
  int channels = 4, bytes_per_channel = 1;
  // JPEG: the start-of-scan markers in the whole file (a progressive JPEG has about ten; each
  // costs the decoder a pass over the image's coefficients). 0 for other formats.
  long long scans = 0;
  // TIFF: the tile the decoder holds whole at once (TileWidth x TileLength), which the header may
  // declare far larger than the image (a 64 x 64 image of one 16384 x 16384 tile: 1 GB for the
  // tile buffer). 0 x 0 when the image has no tiles (strips: a band of the image itself).
  long long tile_width = 0, tile_height = 0;
};

// The declared size, or nullopt when the bytes start with no format above or its header is cut
// short or malformed (the caller refuses such a file: its size cannot be known before decoding).
std::optional<ImageHeader> read_image_header(const std::uint8_t* bytes, std::size_t size);
// The same through a file read a page at a time (a TIFF's first directory may lie anywhere in
// the file). Its loops walk text a line at a time: give it only a TIFF's bytes, the other
// formats' headers from the file's first 64 KB in memory.
std::optional<ImageHeader> read_image_header(const EncodedBytes& bytes);

}  // namespace aief::io

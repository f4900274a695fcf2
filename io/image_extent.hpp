#pragma once
// How many bytes from a file's start its image occupies, by what its header declares, so that
// the decoder is handed the image and not what follows it: a 320 x 240 image padded with zeros
// to 1.5 GB was read whole before decoding (1.6 GB and 5-14 s for JPEG, WebP, BMP, TIFF, PPM).
//   PNG: its chunks up to IEND, walked by their lengths.
//   JPEG: its marker segments and scans up to the end-of-image marker.
//   WebP: the RIFF length.
//   BMP: the pixel data's offset plus its rows (or the compressed size it declares).
//   PNM and PAM: the header plus the raster (binary), or up to the last sample (plain text).
//   TIFF: the end of the farthest of its first directory, the values it points to, and its
//   strips or tiles.
// Other formats, and a file whose walk cannot end where the format says (a JPEG without its
// end-of-image marker), are taken whole: the decoder says what is wrong.
#include <cstdint>
#include <string>

#include "io/encoded_bytes.hpp"
#include "io/image_header.hpp"

namespace aief::io {

// At most bytes.size(). Throws aief::Error for a PNG whose chunk walk meets a chunk that cannot
// be (a type that is not four letters, or a length above 2^31 - 1) before IEND: a damaged file,
// or one padded past its last chunk, refused at once (`name` in the message).
std::uint64_t encoded_image_length(const ImageHeader& header, const EncodedBytes& bytes,
                                   const std::string& name);

}  // namespace aief::io

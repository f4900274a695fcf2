#pragma once
// Binary 8-bit PGM (P5, maxval 255) in and out, without OpenCV: the image input of the tests and
// checks that run where OpenCV is absent (the OpenCV-free build, the aarch64 build under qemu).
#include <string>
#include <string_view>

#include "aief/image.hpp"

namespace aief::test {

// The image in `bytes`, a whole P5 file. Throws aief::Error naming what is wrong: another magic,
// a maxval other than 255, a bad size, or fewer pixel bytes than width x height.
GrayImage parse_pgm(std::string_view bytes);

// parse_pgm of the file at `path`; throws aief::Error when it cannot be read.
GrayImage read_pgm(const std::string& path);

// The P5 bytes of `image` (what parse_pgm reads back).
std::string format_pgm(const GrayImage& image);

}  // namespace aief::test

#pragma once
// Shared by the tests of io/: the image reader's error, a file's bytes, a bundled sample's
// features, the hidden temporaries left in a folder, two Features compared field by field
// (tests/test_image_io.cpp, test_image_limits.cpp, test_hdf5_features.cpp, test_hdf5_merge.cpp,
// test_colmap_database.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "aief/features.hpp"

namespace aief::test {

// What io::read_gray_image says refusing `path`, or "" when it reads the image.
std::string error_of(const std::string& path);

// Every byte of the file at `path`.
std::vector<std::uint8_t> bytes_of(const std::string& path);

// The features of a bundled sample, e.g. sample_features("graf", 1) for graf/img1.png.
Features sample_features(const char* sequence, int index);

// The hidden temporaries (io/temporary_files.hpp) left in `folder`.
std::vector<std::string> temporaries_in(const std::string& folder);

// Every keypoint field, the image size and the descriptors equal (a GoogleTest failure each).
void expect_same(const Features& a, const Features& b);

}  // namespace aief::test

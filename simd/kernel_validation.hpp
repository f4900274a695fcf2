#pragma once
// Bit-exact validation of a kernel set against the scalar reference: used by the test suite
// (tests/test_simd_kernels.cpp) and by `aief validate` on a user's own CPU and images.
#include <string>
#include <vector>

#include "aief/image.hpp"
#include "aief/options.hpp"

namespace aief {

// The kernels checked, in table order, plus "extract" (the whole pipeline at 1 and 2 threads).
const std::vector<std::string>& validated_kernel_names();

// Seeded random images whose widths straddle the vector widths (1..70, 127, 129, 255, 257)
// and heights 1, 3, 37, plus textured ones large enough for the whole pipeline.
std::vector<GrayImage> validation_images();

// "" when `kernel` under `set` gives the same bytes as the scalar reference on every image;
// otherwise where it first differs and both values, e.g. "65x37 row 5 x 17: scalar 23, avx2 0".
std::string validate_kernel(const std::string& kernel, KernelSet set,
                            const std::vector<GrayImage>& images);

}  // namespace aief

#pragma once
// Blurs only what rBRIEF reads. Every sample of a keypoint's rotated pattern lies in a disc
// around it (kSampleHalfWidth, core/kernels/rbrief_describe.hpp), so a blurred row y is read only
// at the columns [x - h, x + h] of the points with |y - point.y| = d <= kSampleReach, h =
// kSampleHalfWidth[d]: on graf the union of those patches is 55-58% of the pyramid's pixels, where
// a blur of whole rows covers nearly all of them.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/kernels/pixel_point.hpp"

namespace aief {

// Rows of one strip: the columns blurred are the union over the points near the strip, so a
// short strip blurs little more than the patches; a taller one makes fewer, longer kernel calls
// (callgrind, AVX2, patch blur stage: graf 3.27 M instructions with strips of 4 rows, 2.77 M with
// 8, 2.71 M with 16, 2.74 M with 24, 2.83 M with 32; 640x480 frame 1.95 M with 8 and 1.87 M with
// 16, its orbslam2 mode 2.48 M and 2.36 M). A multiple of the kernel's bands of 8 rows.
constexpr int kPatchBlurStripRows = 16;

// Blurs rows [y_begin, y_end) of `level` into `dst` (dst row i is level row y_begin + i, as
// KernelTable::gaussian7_rows), at least at every column an rBRIEF sample of one of the points
// reads; other columns of dst are left as they are. points are in raster order (y ascending);
// columns_scratch is reused storage (a bit per column).
void blur_patch_rows(const KernelTable& kernels, ImageView level, MutableImageView dst, int y_begin,
                     int y_end, const PixelPoint* points, int count,
                     std::vector<std::uint64_t>& columns_scratch);

}  // namespace aief

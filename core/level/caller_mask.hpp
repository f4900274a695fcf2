#pragma once
// The caller's mask through the pyramid (Extractor::extract with a mask; docs/opencv.md): where
// detection may take candidates. (Not the entropy mask, which is core/entropy/level_entropy.hpp.)
//
// The caller's mask allows a pixel where it is non-zero. Level 0's mask is that, as 255 / 0.
// Level n's is level n - 1's resized exactly as the pyramid resizes the pixels
// (core/kernels/resize_bilinear_rows.hpp), keeping 255 only where the result is 255, i.e. where
// every source pixel it interpolates is allowed, and 0 elsewhere: cv::ORB's rule (a bilinear resize
// of the mask, then every value below 255 set to 0), with the pyramid's own resize.
//
// Detection takes a FAST candidate only at an allowed pixel of its level, after non-maximum
// suppression (as cv::FAST with a mask drops keypoints after suppression) and before the
// retry rule, the candidate pool and the distribution, so the feature budget is filled inside the
// mask. A block with no allowed pixel is not scored at all. Block entropies, and so which blocks
// F keeps, are those of the pixels, mask or no mask.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/resize_bilinear_rows.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

// Rows [y_begin, y_end) of level 0's mask: 255 where `mask` is non-zero, else 0.
void binarise_mask_rows(ImageView mask, MutableImageView level_mask, int y_begin, int y_end);

// Rows [y_begin, y_end) of level n's mask from level n - 1's (already resized, with `resized`
// from the pyramid's kernel): values below 255 become 0.
void clear_partial_mask_rows(MutableImageView level_mask, int y_begin, int y_end);

// Per block of `grid`: 1 when any pixel of the block is allowed in `level_mask`.
void blocks_allowed(ImageView level_mask, const BlockGrid& grid,
                    std::vector<std::uint8_t>& allowed);

// Bits of the allowed pixels of row `row` over [x_begin, x_end): bit i of word k is pixel
// x_begin + 64 k + i. Writes (x_end - x_begin + 63) / 64 words.
void allowed_bits(const std::uint8_t* row, int x_begin, int x_end, std::uint64_t* words);

}  // namespace aief

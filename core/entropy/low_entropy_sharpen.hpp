#pragma once
// Sharpened low-entropy blocks (LowEntropySharpen, docs/design.md §5, "sharpened low-entropy
// blocks"): an entropy-guided variant after Luo et al.'s entropy + sharpening ORB-SLAM2. Instead of
// dropping a low-entropy block, FAST runs on a copy of the level where it is sharpened:
//   amount of block b   A_b = floor(kUnsharpMaxAmountQ8 * (F_s - h_b) / F_s),
//                       h_b = min(round(256 H_b), F_s), F_s = 256 * kSharpenFullBits
// in 1/256 (2.0 at 0 bits, falling linearly to 0 at kSharpenFullBits and above). A pixel's amount
// is A interpolated linearly between the block centres, first down the block rows (rounded half
// up), then along the pixel row: a0 + floor((a1 - a0) w / 64), the weight w = floor(64 d / D), d
// the distance past centre 0 and D the distance between the centres (the edge blocks' own amount
// beyond the outer centres). So the amount is continuous, with no step at a block border for
// FAST to find. Each row is then core/kernels/unsharp_row.hpp's unsharp mask at those amounts.
// Integers from the block entropies on (which every kernel set computes alike), so the bytes are
// the same under every kernel set and thread count.
#include <cstdint>
#include <vector>

#include "aief/image.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

// Entropy from which a block is left as it is: 6 bits, about the median block of the bundled
// photos (their textured blocks hold 6-7.5 bits, sky and walls 2-5), as for the per-block FAST
// thresholds (core/entropy/entropy_fast_threshold.hpp).
inline constexpr int kSharpenFullBits = 6;

// A_b of a block of `entropy_bits` (>= 0), in 1/256.
int sharpen_amount_q8(double entropy_bits);

// Reused buffers of one level's sharpening.
struct SharpenScratch {
  std::vector<int> block_amounts;           // A_b, row-major
  std::vector<std::int16_t> column_weight;  // per pixel column: weight of the next block column
  std::vector<int> segment_begin;  // per block column c: first pixel column interpolated from c
  std::vector<std::int16_t> row_amounts;    // per block column, the amount at this row, 1/256
  std::vector<std::int16_t> segment_start;  // per pixel: its segment's amount at the left centre
  std::vector<std::int16_t> segment_slope;  // per pixel: its segment's amount difference
  std::vector<std::int16_t> amount_row;     // per pixel of the row, 1/256
  std::vector<std::uint16_t> column_sums;   // the kernel's
};

// After prepare_sharpen_columns (once per level): sharpen_block_column_amounts sets the amount of
// each block column at row y (returns whether any is non-zero), sharpen_amount_row then the
// amounts of that row's pixels (amount_row). Exposed for the tests (continuity across borders).
void prepare_sharpen_columns(const BlockGrid& grid, int width, SharpenScratch& scratch);
bool sharpen_block_column_amounts(const BlockGrid& grid, int y, SharpenScratch& scratch);
void sharpen_amount_row(const BlockGrid& grid, SharpenScratch& scratch);

// The level `pixels` with its blocks (grid, non-empty, over `pixels`) sharpened by their entropies
// (one per block, row-major) into `out`, resized to the level. Returns false, and leaves `out`
// alone, when no block has an amount: detection then reads `pixels` itself.
bool sharpen_low_entropy_blocks(ImageView pixels, const BlockGrid& grid,
                                const std::vector<double>& entropy_bits, const KernelTable& kernels,
                                SharpenScratch& scratch, GrayImage& out);

}  // namespace aief

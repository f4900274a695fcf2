#pragma once
// FAST scores of one block row of a level and its one-pixel ring, in a band of rows as wide as
// the level and a block row tall (plus the ring), so detection reads them from cache instead of
// a whole level's score plane. Band row i holds level row top + i.
#include "aief/image.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

// A band for every block row of a level of `geometry`.
void size_score_band(const LevelGeometry& geometry, GrayImage& band);

// Scores of level rows [y_begin, y_end) and columns [x_begin, x_end) into band rows counted from
// `top`, clipped to [3, size - 3) (suppression near the keypoint area never reads further). A
// run narrower than two AVX-512 batches is widened within the level, so vector kernels see whole
// batches: a few extra scores cost less than a short row's scalar tail.
void compute_score_rows(ImageView pixels, const KernelTable& kernels, int fast_min_threshold,
                        GrayImage& band, int top, int y_begin, int y_end, int x_begin, int x_end);

}  // namespace aief

#pragma once
// The checks a frame passes before any pixel is read: a clear aief::Error instead of a crash.
#include "aief/image.hpp"
#include "aief/options.hpp"

namespace aief {

// Throws aief::Error for an empty image, one without pixel data, a stride below the width, more
// pixels than options.max_image_pixels, a side shorter than 2 * kEdgeBorder + 1, or a pyramid
// (options.n_levels, options.scale_factor) of more pixels, over its levels, than 6 x
// max_image_pixels: the pyramid's memory is bounded as the decoder's is.
void check_image(ImageView image, const ExtractorOptions& options);

}  // namespace aief

#pragma once
// The checks a frame passes before any pixel is read: a clear aief::Error instead of a crash.
#include "aief/image.hpp"
#include "aief/options.hpp"

namespace aief {

// Throws aief::Error for an empty image, one without pixel data, a stride below the width, more
// pixels than options.max_image_pixels, or a side shorter than 2 * kEdgeBorder + 1.
void check_image(ImageView image, const ExtractorOptions& options);

}  // namespace aief

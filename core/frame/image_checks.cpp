#include "core/frame/image_checks.hpp"

#include <sstream>
#include <string>

#include "aief/error.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

namespace {

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The pyramid's pixels, every usable level (the ones built), as multiples of max_image_pixels:
// quality mode's pyramid (scale factor 1.1, 18 levels) sums to 5.6 image areas, the deepest of
// any mode's own options, so every mode takes every image within max_image_pixels; a pyramid of
// tiny scale steps is refused (--scale-factor 1.001 --n-levels 32 on an 8K frame: 31 image areas,
// 4.8 GB, where the decoder's bound on the image itself is 268 MB).
constexpr long long kPyramidAreasAllowed = 6;

void check_pyramid(int width, int height, const ExtractorOptions& options) {
  const long long pixels = pyramid_pixels(width, height, options);
  const long long allowed = kPyramidAreasAllowed * options.max_image_pixels;
  if (pixels > allowed)
    throw Error("image " + size_text(width, height) + " makes a pyramid of " +
                std::to_string(pixels) + " pixels (" + std::to_string(options.n_levels) +
                " levels at scale factor " + number_text(options.scale_factor) +
                "), more than the " + std::to_string(allowed) + " allowed (" +
                std::to_string(kPyramidAreasAllowed) +
                " x max_image_pixels = " + std::to_string(options.max_image_pixels) +
                "; refused before building it: fewer levels or a larger scale factor)");
}

}  // namespace

void check_image(ImageView image, const ExtractorOptions& options) {
  if (image.width <= 0 || image.height <= 0)
    throw Error("image " + size_text(image.width, image.height) + " is empty");
  if (image.data == nullptr)
    throw Error("image " + size_text(image.width, image.height) + " has no pixel data");
  if (image.stride < image.width)
    throw Error("image stride " + std::to_string(image.stride) + " is smaller than its width " +
                std::to_string(image.width));
  const long long pixels = static_cast<long long>(image.width) * image.height;
  if (pixels > options.max_image_pixels)
    throw Error(
        "image " + size_text(image.width, image.height) + " has " + std::to_string(pixels) +
        " pixels, more than max_image_pixels = " + std::to_string(options.max_image_pixels));
  if (!level_is_usable(image.width, image.height))
    throw Error("image " + size_text(image.width, image.height) + " is smaller than the " +
                std::to_string(kEdgeBorder) + "-pixel border (needs at least " +
                std::to_string(2 * kEdgeBorder + 1) + " pixels on each side)");
  check_pyramid(image.width, image.height, options);
}

}  // namespace aief

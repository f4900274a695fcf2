#include "core/frame/image_checks.hpp"

#include <string>

#include "aief/error.hpp"
#include "core/level/level_geometry.hpp"

namespace aief {

namespace {

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
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
}

}  // namespace aief

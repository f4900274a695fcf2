#include "core/kernels/kernel_evidence.hpp"

namespace aief {

std::string where(const GrayImage& image, const std::string& detail) {
  return std::to_string(image.width()) + "x" + std::to_string(image.height()) + " " + detail;
}

std::string first_difference_of_images(const GrayImage& a, const GrayImage& b,
                                       const std::string& set_name) {
  const int w = a.width(), h = a.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (a.data()[y * w + x] != b.data()[y * w + x])
        return std::to_string(w) + "x" + std::to_string(h) + " at (" + std::to_string(x) + ", " +
               std::to_string(y) + "): scalar " + std::to_string(a.data()[y * w + x]) + ", " +
               set_name + " " + std::to_string(b.data()[y * w + x]);
  return "";
}

std::vector<PixelPoint> inner_points(const GrayImage& src, int border, int step) {
  std::vector<PixelPoint> points;
  for (int y = border; y < src.height() - border; y += step)
    for (int x = border; x < src.width() - border; x += step) points.push_back({x, y});
  return points;
}

std::vector<GrayImage> images_of_the_same_sizes(const std::vector<GrayImage>& images) {
  std::vector<GrayImage> out;
  for (const GrayImage& image : images) out.emplace_back(image.width(), image.height());
  return out;
}

}  // namespace aief

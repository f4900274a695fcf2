// Extracts features from a synthetic image through the installed package; prints the count.
// Includes the umbrella header so every installed public header is compiled by a user.
#include <cstdio>
#include <random>
#include <vector>

#include <aief/aief.hpp>

int main() {
  const int width = 320, height = 240;
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height);
  std::mt19937 rng(1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      pixels[static_cast<std::size_t>(y) * width + x] =
          static_cast<unsigned char>(((x / 8 + y / 8) % 2) * 200 + rng() % 40);
  aief::ExtractorOptions options;
  options.n_features = 300;
  const aief::Features features = aief::extract({pixels.data(), width, height, width}, options);
  std::printf("aief %s (%d.%d.%d): %zu keypoints\n", aief::kVersionString, AIEF_VERSION_MAJOR,
              AIEF_VERSION_MINOR, AIEF_VERSION_PATCH, features.keypoints.size());
  return features.keypoints.empty() ? 1 : 0;
}

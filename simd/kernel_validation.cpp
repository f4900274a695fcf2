#include "simd/kernel_validation.hpp"

#include <algorithm>
#include <cstring>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "aief/extractor.hpp"
#include "core/kernels/kernel_evidence.hpp"
#include "core/options/option_names.hpp"
#include "simd/kernels.hpp"

namespace aief {

namespace {

GrayImage random_gray(int width, int height, std::uint32_t seed, bool smooth) {
  GrayImage image(width, height);
  std::mt19937 rng(seed);
  for (int i = 0; i < width * height; ++i) image.data()[i] = static_cast<std::uint8_t>(rng());
  if (smooth && width > 2 &&
      height > 2) {  // a cheap blur: corners of every strength, not just noise
    GrayImage copy = image;
    for (int y = 1; y < height - 1; ++y)
      for (int x = 1; x < width - 1; ++x) {
        int sum = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) sum += copy.data()[(y + dy) * width + x + dx];
        const int stretched = (sum / 9 - 128) * 3 + 128;  // contrast back up after the blur
        image.data()[y * width + x] = static_cast<std::uint8_t>(std::clamp(stretched, 0, 255));
      }
  }
  return image;
}

std::string check_extract(KernelSet set, const GrayImage& src) {
  if (src.width() < 2 * kEdgeBorder + 1 || src.height() < 2 * kEdgeBorder + 1) return "";
  // The default mode (sub-pixel, pool, per-level guard, automatic F) with each descriptor (every
  // one the name table holds, core/options/option_names.hpp), and the paper's conventions.
  std::vector<std::pair<Mode, DescriptorKind>> runs;
  for (const auto& descriptor : option_names::Table<DescriptorKind>::names)
    runs.emplace_back(Mode::aief, descriptor.value);
  runs.emplace_back(Mode::aief_paper, DescriptorKind::rbrief);
  runs.emplace_back(Mode::orbslam2, DescriptorKind::rbrief);
  for (const auto& [mode, descriptor] : runs) {
    ExtractorOptions reference_options = options_for_mode(mode);
    reference_options.auto_threshold = mode == Mode::aief;
    reference_options.descriptor = descriptor;
    reference_options.kernels = KernelSet::scalar;
    reference_options.threads = 1;
    const Features reference = Extractor(reference_options).extract(src.view());
    for (int threads : {1, 2}) {
      ExtractorOptions options = reference_options;
      options.kernels = set;
      options.threads = threads;
      const Features other = Extractor(options).extract(src.view());
      const std::string label = std::string(to_string(mode)) + ", " +
                                std::string(to_string(descriptor)) + ", " +
                                std::to_string(threads) + " thread(s): ";
      if (other.keypoints.size() != reference.keypoints.size())
        return where(src, label + std::to_string(reference.keypoints.size()) +
                              " keypoints with scalar, " + std::to_string(other.keypoints.size()));
      for (std::size_t i = 0; i < reference.keypoints.size(); ++i) {
        const Keypoint &r = reference.keypoints[i], &o = other.keypoints[i];
        if (std::memcmp(&r, &o, sizeof r) != 0 ||
            reference.descriptors[i] != other.descriptors[i]) {
          std::ostringstream out;
          out << label << "keypoint " << i << ": scalar (" << r.x << ", " << r.y << ", "
              << r.angle_deg << "), other (" << o.x << ", " << o.y << ", " << o.angle_deg << ")"
              << (reference.descriptors[i] != other.descriptors[i] ? ", descriptors differ" : "");
          return where(src, out.str());
        }
      }
      if (other.info.entropy_threshold_used != reference.info.entropy_threshold_used ||
          other.info.image_entropy_bits != reference.info.image_entropy_bits)
        return where(src, label + "entropy or threshold differs");
    }
  }
  return "";
}

constexpr const char* kWholePipeline = "extract";

}  // namespace

const std::vector<std::string>& validated_kernel_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const KernelEvidence& entry : kKernelEvidence) out.emplace_back(entry.kernel);
    out.emplace_back(kWholePipeline);
    return out;
  }();
  return names;
}

std::vector<GrayImage> validation_images() {
  std::vector<GrayImage> images;
  std::uint32_t seed = 1;
  std::vector<int> widths;
  for (int w = 1; w <= 70; ++w) widths.push_back(w);
  // Around the vector widths, and rows that end just past the blur's 512-pixel chunks.
  for (int w : {71, 72, 73, 127, 129, 255, 257, 513, 517, 541, 575, 577}) widths.push_back(w);
  for (int w : widths)
    for (int h : {1, 3, 37}) images.push_back(random_gray(w, h, seed++, (w + h) % 2 == 0));
  for (const auto& [w, h] :
       std::vector<std::pair<int, int>>{{64, 64}, {97, 61}, {131, 140}, {257, 129}, {333, 211}})
    images.push_back(random_gray(w, h, seed++, true));
  return images;
}

std::string validate_kernel(const std::string& kernel, KernelSet set,
                            const std::vector<GrayImage>& images) {
  const KernelTable& scalar = kernel_table(KernelSet::scalar);
  const KernelTable& other = kernel_table(set);
  KernelCheck check = nullptr;
  for (const KernelEvidence& entry : kKernelEvidence)
    if (kernel == entry.kernel) check = entry.check;
  if (check == nullptr && kernel != kWholePipeline) return "unknown kernel '" + kernel + "'";
  for (const GrayImage& image : images) {
    const std::string diff =
        check != nullptr ? check(scalar, other, image) : check_extract(set, image);
    if (!diff.empty()) return diff;
  }
  return "";
}

}  // namespace aief

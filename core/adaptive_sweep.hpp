#pragma once
// adapt() with the kernel table given, so tests can count what the sweep computes, and the
// sweep's features per threshold, so tests can match them their own way.
#include <cstdint>
#include <vector>

#include "aief/adapt.hpp"
#include "core/kernel_table.hpp"

namespace aief {

AdaptResult adapt_with_kernels(ImageView a, ImageView b, const ExtractorOptions& options,
                               const SweepOptions& sweep, const KernelTable& kernels);

// One image at one threshold: its features and each feature's identity in the image's analysis
// (candidate index, numbered on through the levels), the same at every threshold that keeps it.
struct ThresholdFeatures {
  Features features;
  std::vector<std::int32_t> ids;
};

// Both images at every threshold F_0 + c S_p of the sweep, c < ceil(E / S_p) (at least one).
struct SweepFeatures {
  double image_entropy_bits = 0;  // E of image A
  std::vector<ThresholdFeatures> a, b;
};

SweepFeatures sweep_features(ImageView a, ImageView b, const ExtractorOptions& options, const SweepOptions& sweep,
                             const KernelTable& kernels);

}  // namespace aief

// aief validate [IMAGE...]: every kernel under every kernel set this CPU runs, against the
// scalar reference, on the given images or on built-in seeded random ones.
#include <cstdio>
#include <iostream>
#include <string>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/frame/image_checks.hpp"
#include "io/image_io.hpp"
#include "simd/kernel_validation.hpp"
#include "simd/kernels.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"

namespace aief::cli {

int run_validate(const Arguments& arguments) {
  const Args args(arguments, {{"--help", "-h", false}});
  if (args.has("--help")) {
    std::cout
        << "usage: aief validate [IMAGE...]\n\n"
        << "Runs every kernel of every kernel set this CPU supports against the scalar reference\n"
        << "(bit for bit) on the images given, or on seeded random images of awkward sizes, and\n"
        << "the whole extraction under each set. Exit status 1 on any mismatch.\n";
    return 0;
  }
  std::vector<GrayImage> images;
  for (const std::string& path : args.positionals()) {
    images.push_back(io::read_gray_image(path));
    try {  // an image no extraction takes would pass the extraction's check untested
      check_image(images.back().view(), ExtractorOptions{});
    } catch (const Error& e) {
      throw Error("cannot validate on '" + path + "': " + e.what());
    }
  }
  // The kernels of keypoints (orientation, descriptors, Hamming distances) are fed the images'
  // keypoints: images of none (a uniform image) test them on nothing, and every row said
  // "identical".
  long long keypoints = 0;
  for (const GrayImage& image : images) keypoints += extract(image.view()).keypoints.size();
  if (!images.empty() && keypoints == 0)
    throw Error("cannot validate on " +
                (images.size() == 1 ? "'" + args.positionals()[0] + "'"
                                    : "these " + std::to_string(images.size()) + " images") +
                ": no keypoint in " + (images.size() == 1 ? "it" : "any") +
                " (a uniform image?), so the kernels of keypoints (orientation, descriptors, "
                "Hamming distances) would test nothing: give an image with corners, or none "
                "(seeded random images)");
  if (images.empty()) images = validation_images();

  const std::vector<KernelSet> sets = available_kernel_sets();
  std::printf("%-22s", "kernel");
  for (KernelSet set : sets) std::printf(" %-12s", std::string(to_string(set)).c_str());
  std::printf("\n");
  bool all_identical = true;
  for (const std::string& kernel : validated_kernel_names()) {
    std::printf("%-22s", kernel.c_str());
    std::string first_mismatch;
    for (KernelSet set : sets) {
      const std::string mismatch = validate_kernel(kernel, set, images);
      std::printf(" %-12s", mismatch.empty() ? "identical" : "MISMATCH");
      if (!mismatch.empty() && first_mismatch.empty())
        first_mismatch = std::string(to_string(set)) + ": " + mismatch;
    }
    std::printf("\n");
    if (!first_mismatch.empty()) {
      std::printf("    first mismatch, %s\n", first_mismatch.c_str());
      all_identical = false;
    }
  }
  std::printf("%s\n",
              all_identical ? "all kernels identical to the scalar reference" : "MISMATCHES FOUND");
  return all_identical ? 0 : 1;
}

}  // namespace aief::cli

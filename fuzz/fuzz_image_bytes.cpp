// libFuzzer: arbitrary bytes as an image file -> the extent its header declares, decode and gray
// conversion (io) -> extract.
// Anything but aief::Error escaping, or any sanitizer report, is a finding.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/image_extent.hpp"
#include "io/image_header.hpp"
#include "io/image_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // A header may claim a huge image: keep decodes small enough for the fuzzer's memory limit.
  setenv("OPENCV_IO_MAX_IMAGE_PIXELS", "4000000", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static aief::Extractor extractor = [] {
    aief::ExtractorOptions options;
    options.n_features = 200;
    options.threads = 1;
    return aief::Extractor(options);
  }();
  try {
    if (const auto header = aief::io::read_image_header(data, size))
      if (aief::io::encoded_image_length(*header, aief::io::EncodedBytes(data, size),
                                         "fuzz input") > size)
        std::abort();
  } catch (const aief::Error&) {
  }
  try {
    const aief::GrayImage image =
        aief::io::decode_gray_image(std::vector<std::uint8_t>(data, data + size), "fuzz input");
    aief::Features features;
    extractor.extract(image.view(), features);
    if (features.keypoints.size() != features.descriptors.size()) std::abort();
  } catch (const aief::Error&) {
  }
  return 0;
}

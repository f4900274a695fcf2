// aief extract IMAGE [-o out.json|out.yml] [--draw out.png] [extractor options]
#include <chrono>
#include <cstdio>
#include <iostream>

#include "aief/extractor.hpp"
#include "io/drawing.hpp"
#include "io/features_files.hpp"
#include "io/image_io.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"

namespace aief::cli {

namespace {

void print_help() {
  std::cout << "usage: aief extract IMAGE [-o OUT.json|OUT.yml] [--draw OUT.png] [options]\n\n"
            << "Keypoints and 256-bit rBRIEF descriptors of one image. Without -o, prints a summary.\n\n"
            << "  -o, --output FILE     features as JSON (.json) or OpenCV FileStorage YAML (.yml)\n"
            << "  --draw FILE           the keypoints drawn over the image, PNG\n"
            << extractor_flags_help();
}

}  // namespace

int run_extract(const Arguments& arguments) {
  std::vector<FlagSpec> spec = extractor_flags();
  spec.push_back({"--output", "-o", true});
  spec.push_back({"--draw", "", true});
  spec.push_back({"--help", "-h", false});
  const Args args(arguments, spec);
  if (args.has("--help")) {
    print_help();
    return 0;
  }
  if (args.positionals().size() != 1) throw UsageError("extract expects one IMAGE (aief extract --help)");
  const ExtractorOptions options = extractor_options(args);
  const std::string& path = args.positionals()[0];

  const GrayImage image = io::read_gray_image(path);
  Extractor extractor(options);
  const auto start = std::chrono::steady_clock::now();
  const Features features = extractor.extract(image.view());
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  if (const auto output = args.get("--output")) io::write_features(*output, path, features, options);
  if (const auto draw = args.get("--draw")) io::draw_keypoints_png(*draw, image.view(), features);

  std::string per_octave;
  for (int n = 0; n < options.n_levels; ++n) {
    int count = 0;
    for (const Keypoint& kp : features.keypoints) count += kp.octave == n ? 1 : 0;
    if (n > 0) per_octave += ' ';
    per_octave += std::to_string(count);
  }
  std::printf("%s: %zu keypoints (per octave %s) in %.2f ms, kernels %s", path.c_str(), features.keypoints.size(),
              per_octave.c_str(), ms, std::string(extractor.kernel_name()).c_str());
  if (options.entropy != EntropyMeasure::off)
    std::printf(", F = %.2f bits%s, %d of %d blocks kept", features.info.entropy_threshold_used,
                features.info.threshold_lowered ? " (lowered: the mask left too few corners)" : "",
                features.info.blocks_kept, features.info.blocks_total);
  std::printf("\n");
  if (const auto output = args.get("--output")) std::printf("features written to %s\n", output->c_str());
  if (const auto draw = args.get("--draw")) std::printf("picture written to %s\n", draw->c_str());
  return 0;
}

}  // namespace aief::cli

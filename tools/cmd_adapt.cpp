// aief adapt A B [-o adapt.json] [--plot curve.png]
#include <cstdio>
#include <iostream>
#include <sstream>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "io/image_io.hpp"
#include "io/json_writer.hpp"
#include "io/plot.hpp"
#include "io/record_fields.hpp"
#include "io/temporary_files.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/output_extension.hpp"
#include "tools/outputs_not_inputs.hpp"
#include "tools/picture_flags.hpp"
#include "tools/read_image.hpp"

namespace aief::cli {

namespace {

// adapt's own flags, each with its --help text.
const std::vector<FlagSpec> kOwnFlags = {
    {"--output", "-o", true, "FILE",
     "{\"threshold\", \"curve\": [{threshold, kept_blocks, keypoints_a, keypoints_b, putative, "
     "inliers, cmr}, ...]} as JSON"},
    {"--plot", "", true, "FILE", "CMR, inliers and keypoints against F, chosen F marked, PNG"}};

void print_help() {
  const SweepOptions d;
  std::cout << "usage: aief adapt A B [-o OUT.json] [--plot OUT.png] [options]\n\n"
            << "Sweeps the entropy threshold F = 0, " << d.step
            << ", ... up to the entropy of A (docs/design.md section 10)\n"
            << "and keeps the F with the highest correct matching rate among those with at least\n"
            << "--min-inliers RANSAC inliers.\n\n"
            << help_of(kOwnFlags) << flags_help<SweepOptions>() << flags_help<MatchOptions>()
            << extractor_flags_help();
}

}  // namespace

int run_adapt(const Arguments& arguments) {
  std::vector<FlagSpec> spec = extractor_flags();
  for (const auto& flags : {flags_of<SweepOptions>(), flags_of<MatchOptions>()})
    spec.insert(spec.end(), flags.begin(), flags.end());
  spec.insert(spec.end(), kOwnFlags.begin(), kOwnFlags.end());
  const std::optional<Args> parsed = command_args(arguments, spec, print_help);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (args.positionals().size() != 2)
    throw UsageError("adapt expects two images A B (aief adapt --help)");
  check_picture_flag(args, "--plot");
  const ExtractorOptions options = extractor_options(args, option_table::Use::sweep);
  require_entropy_to_sweep(args, options, "adapt");
  SweepOptions sweep = options_from_flags<SweepOptions>(args);
  sweep.match = options_from_flags<MatchOptions>(args);

  const std::string &path_a = args.positionals()[0], &path_b = args.positionals()[1];
  refuse_outputs_that_are_inputs(args, {"--output", "--plot"}, {path_a, path_b});
  check_output_extension(args, "--output", ".json", "JSON");
  check_output_folder(args, "--output");
  const GrayImage a = read_image_reporting(path_a, options.max_image_pixels),
                  b = read_image_reporting(path_b, options.max_image_pixels);
  const AdaptResult result = adapt(a.view(), b.view(), options, sweep);

  std::printf("%6s %8s %7s %7s %9s %8s %7s\n", "F", "blocks", "kps_a", "kps_b", "putative",
              "inliers", "CMR%");
  for (std::size_t i = 0; i < result.curve.size(); ++i) {
    const SweepPoint& p = result.curve[i];
    std::printf("%6.2f %8d %7d %7d %9d %8d %7.2f%s\n", p.threshold, p.kept_blocks, p.keypoints_a,
                p.keypoints_b, p.putative, p.inliers, 100.0 * p.cmr,
                static_cast<int>(i) == result.chosen_index ? "  <- chosen" : "");
  }
  if (result.found)
    std::printf("chosen F = %.2f bits (image entropy %.2f bits, %zu thresholds)\n",
                result.threshold, result.image_entropy_bits, result.curve.size());
  else
    std::printf("no threshold reached %d inliers; F = %.2f\n", sweep.min_inliers, result.threshold);

  if (const auto output = args.get("--output")) {
    std::ostringstream text;
    io::JsonWriter json(text);
    json.begin_object();
    json.field("image_a", path_a).field("image_b", path_b).field("threshold", result.threshold);
    json.field("found", result.found).field("image_entropy_bits", result.image_entropy_bits);
    json.field("step", sweep.step)
        .field("min_inliers", sweep.min_inliers)
        .field("matcher", to_string(sweep.match.kind));
    json.key("curve").begin_array();
    for (const SweepPoint& p : result.curve) {
      json.begin_object();
      io::for_each_field(p, [&](std::string_view key, const auto& v) { json.field(key, v); });
      json.end_object();
    }
    json.end_array();
    json.end_object();
    io::write_file_atomically(*output, text.str());
    std::printf("curve written to %s\n", output->c_str());
  }
  if (const auto plot_path = args.get("--plot")) {
    io::Plot plot;
    plot.title = "aief adapt: " + path_a + " -> " + path_b;
    plot.x_label = "entropy threshold F (bits)";
    io::PlotSeries cmr{"CMR", {}, {}}, inliers{"inliers", {}, {}}, kps_a{"keypoints A", {}, {}},
        kps_b{"keypoints B", {}, {}};
    for (const SweepPoint& p : result.curve) {
      for (io::PlotSeries* s : {&cmr, &inliers, &kps_a, &kps_b}) s->x.push_back(p.threshold);
      cmr.y.push_back(100.0 * p.cmr);
      inliers.y.push_back(p.inliers);
      kps_a.y.push_back(p.keypoints_a);
      kps_b.y.push_back(p.keypoints_b);
    }
    plot.panels = {{"correct matching rate CMR (%)", {cmr}},
                   {"inliers and keypoints (count)", {inliers, kps_a, kps_b}}};
    if (result.found) {
      plot.marker_x = result.threshold;
      char label[32];
      std::snprintf(label, sizeof label, "chosen F = %.1f bits", result.threshold);
      plot.marker_label = label;
    }
    io::write_plot_png(*plot_path, plot);
    std::printf("plot written to %s\n", plot_path->c_str());
  }
  return 0;
}

}  // namespace aief::cli

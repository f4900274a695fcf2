// aief match A B [--adaptive] [--matcher K] [-o matches.json] [--draw matches.png], and
// aief match --pairs (its matching: tools/match_pairs.cpp)
#include <cstdio>
#include <iostream>
#include <sstream>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "core/options/option_table.hpp"
#include "io/drawing.hpp"
#include "io/image_io.hpp"
#include "io/json_writer.hpp"
#include "io/record_fields.hpp"
#include "io/temporary_files.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/match_pairs.hpp"
#include "tools/output_extension.hpp"
#include "tools/outputs_not_inputs.hpp"
#include "tools/picture_flags.hpp"
#include "tools/read_image.hpp"

namespace aief::cli {

namespace {

// The flags of a pair of images beside the matcher's and the extractor's; --pairs matches the
// features of a file, so only the matcher's flags and these apply to it.
// Each with its --help text (-o once: the pair's).
const std::vector<FlagSpec> kImagePairFlags = {
    {"--adaptive", "", false, "",
     "choose the entropy threshold F by the sweep over this pair (aief adapt)"},
    {"--output", "-o", true, "FILE", "matches, inliers and homography as JSON"},
    {"--draw", "", true, "FILE", "both images side by side, inliers green, outliers red, PNG"}};
const std::vector<FlagSpec> kPairsFlags = {
    {"--pairs", "", true, "FILE",
     "hloc pairs (\"name0 name1\" per line) matched from --features-file "
     "(aief extract --format h5) into -o MATCHES.h5, hloc's matches0 / matching_scores0 layout; "
     "only the matcher's flags apply (the features are as extracted)"},
    {"--features-file", "", true, "FILE",
     "with --pairs: the HDF5 features file (its earlier spelling,\n"
     "--features, is still accepted with --pairs)"},
    {"--output", "-o", true}};

void print_help() {
  std::cout << "usage: aief match A B [--adaptive] [--matcher K] [-o OUT.json] [--draw OUT.png]\n"
            << "       aief match --pairs PAIRS.txt --features-file FEATURES.h5 -o MATCHES.h5 "
               "[--matcher K]\n\n"
            << "Extracts both images, matches them, estimates the homography A -> B with RANSAC (3 "
               "px).\n\n"
            << flags_help<MatchOptions>() << help_of(kImagePairFlags) << help_of(kPairsFlags)
            << extractor_flags_help();
}

std::vector<Point2> points_of(const Features& features, const std::vector<Match>& matches,
                              bool query) {
  std::vector<Point2> points;
  points.reserve(matches.size());
  for (const Match& m : matches) {
    const Keypoint& kp = features.keypoints[static_cast<std::size_t>(query ? m.query : m.train)];
    points.push_back({kp.x, kp.y});
  }
  return points;
}

// --pairs: the flags that do not apply to a features file are refused, never ignored. The features
// file was --features before it had a flag of its own (--features is --n-features' earlier
// spelling): with --pairs and no --features-file, it is still the file.
int run_pairs(const Args& args) {
  std::vector<FlagSpec> applying = flags_of<MatchOptions>();
  applying.insert(applying.end(), kPairsFlags.begin(), kPairsFlags.end());
  std::optional<std::string> features_file = args.get("--features-file");
  const std::string n_features(option_table::row("n_features").cli_flag);
  if (!features_file && args.spelled(n_features) == "--features") {
    features_file = args.get(n_features);
    applying.push_back({n_features, "", true});
    std::cerr << "aief: note: --pairs' features file is --features-file now (--features still "
                 "accepted)\n";
  }
  const std::vector<std::string> outside = flags_outside(args, applying);
  if (!outside.empty()) {
    std::string listed;
    for (const std::string& flag : outside)
      listed += (listed.empty() ? "" : ", ") + args.spelled(flag);
    throw UsageError(
        "--pairs matches the features of --features-file as they were extracted: " + listed +
        (outside.size() == 1 ? " does" : " do") + " not apply (aief match --help)");
  }
  if (!features_file || !args.get("--output"))
    throw UsageError("--pairs needs --features-file FEATURES.h5 and -o MATCHES.h5");
  check_output_extension(args, "--output", ".h5", "the matches as HDF5 (hloc's layout)");
  check_output_folder(args, "--output");
  return run_match_pairs(args, *features_file, options_from_flags<MatchOptions>(args));
}

}  // namespace

int run_match(const Arguments& arguments) {
  std::vector<FlagSpec> spec = extractor_flags();
  for (const auto& flags : {flags_of<MatchOptions>(), kImagePairFlags, kPairsFlags})
    for (const FlagSpec& flag : flags) {
      bool known = false;
      for (const FlagSpec& seen : spec) known = known || seen.name == flag.name;
      if (!known) spec.push_back(flag);
    }
  const std::optional<Args> parsed = command_args(arguments, spec, print_help);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (args.has("--pairs")) return run_pairs(args);
  const MatchOptions match_options = options_from_flags<MatchOptions>(args);
  if (args.positionals().size() != 2)
    throw UsageError("match expects two images A B (aief match --help)");
  check_picture_flag(args, "--draw");
  const ExtractorOptions options = extractor_options(
      args, args.has("--adaptive") ? option_table::Use::sweep : option_table::Use::extraction);
  refuse_carried_threshold(args, options, "match A B");

  const std::string &path_a = args.positionals()[0], &path_b = args.positionals()[1];
  refuse_outputs_that_are_inputs(args, {"--output", "--draw"}, {path_a, path_b});
  check_output_extension(args, "--output", ".json", "JSON");
  check_output_folder(args, "--output");
  const GrayImage a = read_image_reporting(path_a, options.max_image_pixels),
                  b = read_image_reporting(path_b, options.max_image_pixels);

  Features features_a, features_b;
  std::vector<Match> matches;
  HomographyResult homography;
  double threshold = options.entropy_threshold;
  if (args.has("--adaptive")) {
    SweepOptions sweep;
    sweep.match = match_options;
    ExtractorOptions sweep_options = options;
    require_entropy_to_sweep(args, sweep_options, "match --adaptive");
    AdaptResult result = adapt(a.view(), b.view(), sweep_options, sweep);
    threshold = result.threshold;
    features_a = std::move(result.features_a);
    features_b = std::move(result.features_b);
    matches = std::move(result.matches);
    homography = std::move(result.homography);
  } else {
    Extractor extractor(options);
    features_a = extractor.extract(a.view());
    features_b = extractor.extract(b.view());
    matches = match_features(features_a, features_b, match_options);
    homography = find_homography_ransac(points_of(features_a, matches, true),
                                        points_of(features_b, matches, false));
    threshold = features_a.info.entropy_threshold_used;
  }
  const int inliers = homography.found ? homography.inliers : 0;
  const double cmr =
      matches.empty() ? 0.0 : static_cast<double>(inliers) / static_cast<double>(matches.size());

  std::printf("%zu + %zu keypoints, %zu putative matches (%s), %d inliers, CMR %.2f%%",
              features_a.keypoints.size(), features_b.keypoints.size(), matches.size(),
              std::string(to_string(match_options.kind)).c_str(), inliers, 100.0 * cmr);
  if (options.entropy != EntropyMeasure::off) std::printf(", F = %.2f", threshold);
  if (!homography.found) std::printf(" (no homography: %s)", homography.failure.c_str());
  std::printf("\n");

  if (const auto output = args.get("--output")) {
    std::ostringstream text;
    io::JsonWriter json(text);
    json.begin_object();
    json.field("image_a", path_a)
        .field("image_b", path_b)
        .field("matcher", to_string(match_options.kind));
    json.field("entropy_threshold", threshold)
        .field("keypoints_a", static_cast<int>(features_a.keypoints.size()));
    json.field("keypoints_b", static_cast<int>(features_b.keypoints.size()));
    json.field("putative", static_cast<int>(matches.size()))
        .field("inliers", inliers)
        .field("cmr", cmr);
    json.field("homography_found", homography.found);
    json.key("homography").begin_array();
    for (double v : homography.H) json.value(v);
    json.end_array();
    json.key("matches").begin_array();
    for (std::size_t i = 0; i < matches.size(); ++i) {
      const Keypoint& ka = features_a.keypoints[static_cast<std::size_t>(matches[i].query)];
      const Keypoint& kb = features_b.keypoints[static_cast<std::size_t>(matches[i].train)];
      json.begin_object();
      io::for_each_field(matches[i], [&](std::string_view key, int v) { json.field(key, v); });
      json.field("xa", ka.x).field("ya", ka.y).field("xb", kb.x).field("yb", kb.y);
      json.field("inlier", homography.found && homography.inlier_mask[i] != 0).end_object();
    }
    json.end_array();
    json.end_object();
    io::write_file_atomically(*output, text.str());
    std::printf("matches written to %s\n", output->c_str());
  }
  if (const auto draw = args.get("--draw")) {
    io::draw_matches_png(*draw, a.view(), features_a, b.view(), features_b, matches,
                         homography.inlier_mask);
    std::printf("picture written to %s\n", draw->c_str());
  }
  return 0;
}

}  // namespace aief::cli

// aief extract IMAGE [-o FILE] [--draw out.png] [extractor options], or --batch: the formats are
// io/feature_formats.cpp's rows.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/drawing.hpp"
#include "io/feature_formats.hpp"
#include "io/image_io.hpp"
#include "io/option_record.hpp"
#include "tools/batch.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/output_extension.hpp"
#include "tools/outputs_not_inputs.hpp"
#include "tools/picture_flags.hpp"
#include "tools/read_image.hpp"

namespace aief::cli {

namespace {

using Layout = io::FeatureFormat::Layout;

// The formats of a layout joined: their names ("json|yml|npz"), or "OUT.json|OUT.yml|OUT.npz"
// (`prefix` before each usual extension, name false).
std::string joined(Layout layout, const std::string& separator, bool names,
                   const std::string& prefix = "") {
  std::string text;
  for (const io::FeatureFormat* format : io::feature_formats_of(layout))
    text += (text.empty() ? prefix : separator + prefix) +
            (names ? format->name : format->extensions.front());
  return text;
}

// "a, b or c" of each format of `layout` as `item` writes it.
template <class Item>
std::string listed(Layout layout, Item item) {
  const std::vector<const io::FeatureFormat*> formats = io::feature_formats_of(layout);
  std::string text;
  for (std::size_t i = 0; i < formats.size(); ++i) {
    if (i > 0) text += i + 1 == formats.size() ? " or " : ", ";
    text += item(*formats[i], i);
  }
  return text;
}

// "JSON (.json), OpenCV FileStorage YAML (.yml) or numpy (.npz)".
std::string described(Layout layout) {
  return listed(layout, [](const io::FeatureFormat& format, std::size_t) {
    return std::string(format.what) + " (" + format.extensions.front() + ")";
  });
}

// The default --format: the first file-per-image format.
const char* default_format() {
  return io::feature_formats_of(Layout::file_per_image).front()->name;
}

// extract's own flags, each with its --help text.
std::vector<FlagSpec> own_flags() {
  const std::string per_batch = joined(Layout::one_file_per_batch, "|", true);
  return {
      {"--output", "-o", true, "FILE", "features as " + described(Layout::file_per_image)},
      {"--draw", "", true, "FILE", "the keypoints drawn over the image, PNG"},
      {"--batch", "", true, "LIST|DIR",
       "every image of a folder (recursively, symlinks followed) or of a list file "
       "(one path per line). "
       "Each image's name is its path below DIR as listed (or its line), never the symlink "
       "target; its output is OUTDIR/<name>.<format>, folders mirrored: "
       "sub/x.png -> OUTDIR/sub/x.png.json. "
       "Resumable: an output recording this image's name, size and time and these options is "
       "kept, any other is redone (the reason said); outputs appear atomically. "
       "A bad image is reported and skipped. Exit 1 if any failed."},
      {"--format", "", true, "F",
       listed(Layout::file_per_image,
              [](const io::FeatureFormat& format, std::size_t i) {
                return std::string(format.name) + (i == 0 ? " (default)" : "");
              }) +
           ": a file per image in OUTDIR;\n" + per_batch + ": one file, " +
           described(Layout::one_file_per_batch) +
           ", a group per image named by its path below DIR "
           "(resumes at the first image not complete in it; one file per shard, then aief "
           "merge); without --format, an -o ending in its extension is that format"},
      {"--shard", "", true, "i/n",
       "this run takes images i, i+n, i+2n ... of the list sorted by name,\n"
       "0 <= i < n: machines split a collection, no coordinator. Slurm:\n"
       "  --shard $((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN))/$SLURM_ARRAY_TASK_COUNT\n"
       "(right for 0- and 1-based arrays alike)"},
  };
}

void print_help() {
  const std::string per_image = joined(Layout::file_per_image, "|", true);
  const std::string per_batch = joined(Layout::one_file_per_batch, "|", true);
  std::cout << "usage: aief extract IMAGE [-o " << joined(Layout::file_per_image, "|", false, "OUT")
            << "] [--draw OUT.png] [options]\n"
            << "       aief extract --batch LIST|DIR -o OUTDIR [--format " << per_image
            << "] [--shard i/n] [options]\n"
            << "       aief extract --batch LIST|DIR -o FEATURES"
            << joined(Layout::one_file_per_batch, "|", false) << " --format " << per_batch
            << " [--shard i/n] [options]\n\n"
            << "Keypoints and 256-bit descriptors (rBRIEF, or the box descriptor: --descriptor) of "
               "one image.\nWithout -o, prints a summary.\n\n"
            << help_of(own_flags()) << extractor_flags_help();
}

int run_extract_batch(const Args& args) {
  if (!args.positionals().empty())
    throw UsageError("--batch takes its images from LIST|DIR, not from positional arguments");
  BatchSettings settings;
  settings.input = *args.get("--batch");
  const auto output = args.get("--output");
  if (!output) throw UsageError("--batch needs -o OUTDIR");
  settings.output_dir = *output;
  // Without --format, an output named as one file per batch (d.h5) is that format: before, d.h5
  // became a folder of JSON files.
  const io::FeatureFormat* named_as = io::feature_format_of_path(settings.output_dir);
  const bool one_file =
      named_as && named_as->layout == io::FeatureFormat::Layout::one_file_per_batch;
  settings.format = args.get("--format").value_or(one_file ? named_as->name : default_format());
  if (!io::feature_format_named(settings.format))
    throw UsageError("--format expects " + io::feature_format_names() + ", got '" +
                     settings.format + "'");
  // An output named as another format (`--format json -o oo.h5`) made a folder oo.h5 of JSON.
  if (named_as && named_as->name != settings.format)
    throw UsageError("-o " + settings.output_dir + " names " + std::string(named_as->name) +
                     " by its extension, but --format " + settings.format +
                     " was asked: " + "drop --format, or name the output otherwise");
  if (const auto shard = args.get("--shard")) {
    try {
      const Shard parsed = parse_shard(*shard);
      settings.shard_index = parsed.index;
      settings.shard_count = parsed.count;
    } catch (const Error& e) {
      throw UsageError(e.what());
    }
  }
  settings.options = extractor_options(args);
  if (settings.options.carried_threshold && settings.shard_count > 1)
    throw UsageError(
        "--shard splits a collection between runs, but --entropy-threshold carried carries F from "
        "frame to frame of one video (each frame's F depends on the frames before it): extract "
        "each "
        "video in one run, and split by video instead");
  const BatchSummary summary = run_batch(settings);
  std::printf("batch: %d images in this shard: %d extracted", summary.images, summary.extracted);
  if (summary.replaced > 0)
    std::printf(" (%d replacing the output of another or a changed image)", summary.replaced);
  if (summary.redone > 0)
    std::printf(" (%d redone: %s)", summary.redone, io::listed(summary.redone_for).c_str());
  std::printf(", %d already done, %d failed; %lld keypoints\n", summary.skipped, summary.failed,
              summary.keypoints);
  for (const std::string& failure : summary.failures)
    std::printf("  failed: %s\n", failure.c_str());
  if (!summary.of_no_input.empty())
    std::fprintf(
        stderr,
        "aief: note: '%s' holds %zu image(s) that are none of this run's inputs (deleted or "
        "moved since an earlier run wrote them? the first: '%s'): kept, and merge carries "
        "them on\n",
        settings.output_dir.c_str(), summary.of_no_input.size(),
        summary.of_no_input.front().c_str());
  if (!summary.stopped.empty())
    throw Error(summary.stopped +
                "\nbatch stopped: " + std::to_string(summary.on_disk + summary.skipped) + " of " +
                std::to_string(summary.images) +
                " images are done; run the same command again to resume");
  return summary.failed > 0 ? 1 : 0;
}

}  // namespace

int run_extract(const Arguments& arguments) {
  std::vector<FlagSpec> spec = extractor_flags();
  for (const FlagSpec& flag : own_flags()) spec.push_back(flag);
  const std::optional<Args> parsed = command_args(arguments, spec, print_help);
  if (!parsed) return 0;
  const Args& args = *parsed;
  // Flags that belong to the other form are refused, never dropped.
  if (args.has("--batch") && args.has("--draw"))
    throw UsageError("--draw pictures one image; --batch writes features only");
  for (const char* flag : {"--format", "--shard"})
    if (!args.has("--batch") && args.has(flag))
      throw UsageError(std::string(flag) + " applies to --batch only");
  if (args.has("--batch")) return run_extract_batch(args);
  if (args.positionals().size() != 1)
    throw UsageError("extract expects one IMAGE (aief extract --help)");
  if (const auto output = args.get("--output"); output && !io::is_features_file_name(*output))
    throw UsageError("-o " + *output + ": the output must end in " +
                     io::feature_format_extensions(io::FeatureFormat::Layout::file_per_image));
  check_output_folder(args, "--output");
  if (const auto output = args.get("--output"))
    io::check_features_file_can_hold(*output, args.positionals()[0], args.positionals()[0]);
  check_picture_flag(args, "--draw");
  const ExtractorOptions options = extractor_options(args);
  refuse_carried_threshold(args, options, "extract IMAGE");
  const std::string& path = args.positionals()[0];
  refuse_outputs_that_are_inputs(args, {"--output", "--draw"}, {path});

  std::vector<std::string> warnings;
  const GrayImage image = read_image_reporting(path, options.max_image_pixels, &warnings);
  io::SourceRecord source = io::source_record_of(path, path);
  source.warnings = warnings;
  Extractor extractor(options);
  const auto start = std::chrono::steady_clock::now();
  const Features features = extractor.extract(image.view());
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  if (const auto output = args.get("--output"))
    io::write_features(*output, path, features, options, source);
  if (const auto draw = args.get("--draw")) io::draw_keypoints_png(*draw, image.view(), features);

  std::string per_octave;
  for (int n = 0; n < options.n_levels; ++n) {
    int count = 0;
    for (const Keypoint& kp : features.keypoints) count += kp.octave == n ? 1 : 0;
    if (n > 0) per_octave += ' ';
    per_octave += std::to_string(count);
  }
  std::printf("%s: %zu keypoints (per octave %s) in %.2f ms, kernels %s", path.c_str(),
              features.keypoints.size(), per_octave.c_str(), ms,
              std::string(extractor.kernel_name()).c_str());
  if (options.entropy != EntropyMeasure::off)
    std::printf(", F = %.2f bits%s, %d of %d blocks kept", features.info.entropy_threshold_used,
                features.info.threshold_lowered ? " (lowered: the mask left too few corners)" : "",
                features.info.blocks_kept, features.info.blocks_total);
  std::printf("\n");
  if (const auto output = args.get("--output"))
    std::printf("features written to %s\n", output->c_str());
  if (const auto draw = args.get("--draw")) std::printf("picture written to %s\n", draw->c_str());
  return 0;
}

}  // namespace aief::cli

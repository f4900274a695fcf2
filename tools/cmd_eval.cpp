// aief eval --dataset DIR [--sequences a,b] [--pairs 1-2|all] [-o report.md]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string_view>

#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "io/image_io.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/eval/dataset.hpp"
#include "tools/eval/methods.hpp"
#include "tools/eval/report.hpp"
#include "tools/outputs_not_inputs.hpp"
#include "tools/progress.hpp"
#include "tools/read_image.hpp"

namespace aief::cli {

namespace {

// The extractor options each row sets itself, whose flags eval neither takes nor lists: the mode
// (each row names its own), F (the row's way of choosing it), the carried F's period (a video's,
// not a pair's) and the threads (one: per-core times, as the paper's and OpenCV's).
const std::vector<std::string_view> kSetByEachRow = {"mode", "entropy_threshold", "carry_every",
                                                     "threads"};

std::vector<FlagSpec> own_flags();

void print_help() {
  std::cout
      << "usage: aief eval --dataset DIR [--sequences a,b,...] [--pairs 1-2|all] [-o REPORT.md]\n"
      << "                 [matcher options] [--repeat N] [--methods LIST] [extractor options]\n\n"
      << "Runs ORB-SLAM2 mode, Quadtree + entropy, AIEF paper and AIEF (adaptive F and pair-free "
         "automatic F),\n"
      << "OpenCV ORB, SIFT, AKAZE and BRISK on the Oxford affine sequences in DIR (<seq>/img1..6, "
         "H1to2p..6p):\n"
      << "the paper's four tables (img1 -> img2 of graf, leuven, boat, bikes) beside its figures, "
         "and\n"
      << "correct matches, accuracy and homography success under the ground truth. Writes "
         "REPORT.md,\n"
      << "REPORT.json and one plot per sequence in REPORT_plots/.\n\n"
      << help_of(own_flags()) << flags_help<MatchOptions>() << "\n"
      << "extractor options of the AIEF rows (--mode aief; the other rows keep their mode's), as "
         "in\n"
      << "aief extract; each row sets its own mode, F and one thread:\n"
      << extractor_flags_help_except(kSetByEachRow);
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// The JSON keys of every row, comma-separated.
std::string method_keys_text() {
  std::string text;
  for (const eval::Method& method : eval::kAllMethods)
    text += (text.empty() ? "" : ", ") + eval::method_key(method);
  return text;
}

// eval's own flags, each with its --help text.
std::vector<FlagSpec> own_flags() {
  return {
      {"--dataset", "", true, "DIR", "the Oxford sequences"},
      {"--sequences", "", true, "LIST", "comma-separated (default all eight present)"},
      {"--pairs", "", true, "P", "1-2 or all (1 -> 2..6; default all)"},
      {"--output", "-o", true, "FILE", "the markdown report (default evaluation.md)"},
      {"--repeat", "", true, "N", "interleaved timing rounds per pair, median (default 5)"},
      {"--methods", "", true, "LIST",
       "comma-separated JSON keys of the rows to run (default all):\n" + method_keys_text() +
           ";\nor any mode, F as the mode sets it (aief, quality), "
           "swept over the pair (MODE_adaptive) or automatic (MODE_auto): quality_auto"},
  };
}

cv::Mat as_mat(const GrayImage& image) {
  return cv::Mat(image.height(), image.width(), CV_8UC1, const_cast<std::uint8_t*>(image.data()));
}

std::vector<FlagSpec> flags_of_eval() {
  std::vector<FlagSpec> spec = flags_of<MatchOptions>();
  const std::vector<FlagSpec> own = own_flags();
  spec.insert(spec.end(), own.begin(), own.end());
  const std::vector<FlagSpec> extractor = extractor_flags_except(kSetByEachRow);
  spec.insert(spec.end(), extractor.begin(), extractor.end());
  return spec;
}

// The sequences asked for, or all eight of the Oxford set present in the dataset.
std::vector<std::string> sequences_of(const Args& args, const std::string& dataset) {
  if (const auto listed = args.get("--sequences")) return split(*listed);
  std::vector<std::string> present;
  for (const std::string& s : eval::kAllSequences)
    if (std::filesystem::is_directory(std::filesystem::path(dataset) / s)) present.push_back(s);
  return present;
}

// The rows --methods names, or every row.
std::vector<eval::Method> methods_of(const Args& args) {
  const auto keys = args.get("--methods");
  if (!keys) return eval::kAllMethods;
  std::vector<eval::Method> methods;
  try {
    for (const std::string& key : split(*keys)) methods.push_back(eval::parse_method_key(key));
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (methods.empty()) throw UsageError("--methods needs at least one method");
  return methods;
}

// The matcher's rows, as in match; the AIEF rows' extractor options, as in extract.
eval::EvalSettings settings_of(const Args& args) {
  eval::EvalSettings settings;
  settings.timing_repeats = args.get_int("--repeat", settings.timing_repeats, 1, 1000);
  settings.match = options_from_flags<MatchOptions>(args);
  if (settings.match.kind == MatcherKind::guided)
    throw UsageError(
        "--matcher guided matches two views of a 3D scene by their epipolar "
        "geometry; eval's pairs are related by a homography (aief match --pairs "
        "takes it, docs/colmap.md)");
  // The rows turn the automatic F on: its options are taken without it (Use::evaluation).
  settings.aief = extractor_options(args, option_table::Use::evaluation);
  return settings;
}

// What the command line asks for, checked before any work.
struct EvalCommand {
  std::string dataset, output;
  bool all_pairs = true;
  std::vector<std::string> sequences;
  std::vector<eval::Method> methods;
  eval::EvalSettings settings;
};

EvalCommand command_of(const Args& args) {
  EvalCommand command;
  if (!args.positionals().empty())
    throw UsageError("eval takes no positional argument (did you mean --dataset?)");
  const auto dataset = args.get("--dataset");
  if (!dataset) throw UsageError("eval needs --dataset DIR");
  command.dataset = *dataset;
  const std::string pairs_text = args.get("--pairs").value_or("all");
  if (pairs_text != "all" && pairs_text != "1-2")
    throw UsageError("--pairs expects 1-2 or all, got '" + pairs_text + "'");
  command.all_pairs = pairs_text == "all";
  command.sequences = sequences_of(args, command.dataset);
  command.settings = settings_of(args);
  command.methods = methods_of(args);
  // The extractor flags set the aief mode's own rows only (eval::Method): without one they would
  // do nothing.
  bool an_aief_row = false;
  for (const eval::Method& method : command.methods)
    an_aief_row =
        an_aief_row || (method.mode == Mode::aief && method.baseline == eval::Baseline::none);
  if (!an_aief_row) {
    std::string given;
    for (const FlagSpec& flag : extractor_flags_except(kSetByEachRow))
      if (args.has(flag.name)) given += (given.empty() ? "" : ", ") + args.spelled(flag.name);
    if (!given.empty())
      throw UsageError(given + " set" + (given.find(',') == std::string::npos ? "s" : "") +
                       " the options of the aief mode's rows (aief, aief_adaptive, aief_auto), "
                       "and --methods names none of them: the other rows keep their own");
  }
  if (command.settings.aief.entropy == EntropyMeasure::off)
    for (const eval::Method& method : command.methods)
      if (method.mode == Mode::aief && method.baseline == eval::Baseline::none &&
          method.threshold != eval::ThresholdChoice::mode)
        throw UsageError("--entropy off leaves " + eval::method_key(method) +
                         " no entropy threshold to choose");
  command.output = args.get("--output").value_or("evaluation.md");
  return command;
}

// Every row on every pair of `run`, one pair after the other (image A read once per sequence),
// then the pair's extraction times, interleaved.
void evaluate(eval::EvalRun& run, const eval::EvalSettings& settings) {
  cv::setNumThreads(1);  // per-core times for every row
  const auto start = std::chrono::steady_clock::now();
  Progress progress("eval", static_cast<int>(run.pairs.size() * run.methods.size()));
  const long long max_pixels = settings.aief.max_image_pixels;
  std::string loaded_a;
  GrayImage image_a;
  for (const eval::PairInput& pair : run.pairs) {
    if (pair.path_a != loaded_a) {
      image_a = read_image_reporting(pair.path_a, max_pixels);
      loaded_a = pair.path_a;
    }
    const GrayImage image_b = read_image_reporting(pair.path_b, max_pixels);
    std::vector<eval::PairResult> row;
    for (const eval::Method& method : run.methods) {
      row.push_back(
          eval::run_method(method, as_mat(image_a), as_mat(image_b), pair.truth, settings));
      progress.step(pair.sequence + " 1-" + std::to_string(pair.target) + " " +
                    eval::method_key(method));
    }
    eval::time_extractions(run.methods, as_mat(image_a), settings, row, run.load);
    run.results.push_back(std::move(row));
  }
  progress.finish();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int run_eval(const Arguments& arguments) {
  const std::optional<Args> parsed = command_args(arguments, flags_of_eval(), print_help);
  if (!parsed) return 0;
  const Args& args = *parsed;
  const EvalCommand command = command_of(args);
  eval::EvalRun run;
  run.pairs = eval::find_pairs(command.dataset, command.sequences, command.all_pairs);
  if (run.pairs.empty()) throw Error("no sequence found in '" + command.dataset + "'");
  std::vector<std::string> inputs;
  for (const eval::PairInput& pair : run.pairs)
    inputs.insert(inputs.end(), {pair.path_a, pair.path_b, pair.truth_path});
  const std::string json_path =
      std::filesystem::path(command.output).replace_extension(".json").string();
  refuse_outputs_that_are_inputs({{"-o", command.output}, {"-o (its data)", json_path}}, inputs);
  run.methods = command.methods;
  run.matcher = std::string(to_string(command.settings.match.kind));
  run.timing_rounds = command.settings.timing_repeats;
  evaluate(run, command.settings);
  const eval::ReportFiles files = eval::write_reports(run, command.output);
  std::printf(
      "evaluated %zu pairs x %zu methods in %.0f s\nreport: %s\ndata: %s\nplots: %s/ (%zu)\n",
      run.pairs.size(), run.methods.size(), run.seconds, files.markdown.c_str(), files.json.c_str(),
      files.plot_folder.c_str(), files.plots.size());
  return 0;
}

}  // namespace aief::cli

// aief eval --dataset DIR [--sequences a,b] [--pairs 1-2|all] [-o report.md]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "io/image_io.hpp"
#include "io/json_writer.hpp"
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

void print_help() {
  std::cout
      << "usage: aief eval --dataset DIR [--sequences a,b,...] [--pairs 1-2|all] [-o REPORT.md]\n\n"
      << "Runs ORB-SLAM2 mode, Quadtree + entropy, AIEF paper and AIEF (adaptive F and pair-free "
         "automatic F),\n"
      << "OpenCV ORB and OpenCV SIFT on the Oxford affine sequences in DIR (<seq>/img1..6, "
         "H1to2p..6p):\n"
      << "the paper's four tables (img1 -> img2 of graf, leuven, boat, bikes) beside its figures, "
         "and\n"
      << "correct matches, accuracy and homography success under the ground truth. Writes "
         "REPORT.md,\n"
      << "REPORT.json and one plot per sequence in REPORT_plots/.\n\n"
      << "  --dataset DIR         the Oxford sequences\n"
      << "  --sequences LIST      comma-separated (default all eight present)\n"
      << "  --pairs P             1-2 or all (1 -> 2..6; default all)\n"
      << "  -o, --output FILE     the markdown report (default evaluation.md)\n"
      << flags_help<MatchOptions>()
      << "  --repeat N            interleaved timing rounds per pair, median (default 5)\n"
      << "  --methods LIST        comma-separated JSON keys of the rows to run (default all):\n"
      << "                        orbslam2, quadtree_entropy, aief_paper_adaptive, "
         "aief_paper_auto,\n"
      << "                        aief_adaptive, aief_auto, opencv_orb, opencv_sift\n"
      << "  --pool P|inf, --coordinates C, --subpixel on|off, --starvation-guard G, --ranking R,\n"
      << "  --auto-two-classes on|off\n"
      << "                        the AIEF rows' options, as in aief extract (defaults: the "
         "library's)\n";
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

cv::Mat as_mat(const GrayImage& image) {
  return cv::Mat(image.height(), image.width(), CV_8UC1, const_cast<std::uint8_t*>(image.data()));
}

}  // namespace

int run_eval(const Arguments& arguments) {
  std::vector<FlagSpec> spec = flags_of<MatchOptions>();
  spec.insert(spec.end(), {{"--dataset", "", true},
                           {"--sequences", "", true},
                           {"--pairs", "", true},
                           {"--output", "-o", true},
                           {"--repeat", "", true},
                           {"--methods", "", true},
                           {"--pool", "", true},
                           {"--coordinates", "", true},
                           {"--subpixel", "", true},
                           {"--starvation-guard", "", true},
                           {"--ranking", "", true},
                           {"--auto-two-classes", "", true},
                           {"--help", "-h", false}});
  const Args args(arguments, spec);
  if (args.has("--help")) {
    print_help();
    return 0;
  }
  if (!args.positionals().empty())
    throw UsageError("eval takes no positional argument (did you mean --dataset?)");
  const auto dataset = args.get("--dataset");
  if (!dataset) throw UsageError("eval needs --dataset DIR");
  const std::string pairs_text = args.get("--pairs").value_or("all");
  if (pairs_text != "all" && pairs_text != "1-2")
    throw UsageError("--pairs expects 1-2 or all, got '" + pairs_text + "'");
  std::vector<std::string> sequences =
      args.get("--sequences") ? split(*args.get("--sequences")) : eval::kAllSequences;
  if (!args.get("--sequences")) {  // all eight, or those present
    std::vector<std::string> present;
    for (const std::string& s : sequences)
      if (std::filesystem::is_directory(std::filesystem::path(*dataset) / s)) present.push_back(s);
    sequences = present;
  }
  eval::EvalSettings settings;
  settings.timing_repeats = args.get_int("--repeat", settings.timing_repeats, 1, 1000);
  settings.match = options_from_flags<MatchOptions>(args);  // the matcher's rows, as in match
  settings.aief =
      extractor_options(args, option_table::Use::evaluation);  // the AIEF rows' flags, as in
                                                               // extract
  std::vector<eval::Method> methods = eval::kAllMethods;
  if (const auto keys = args.get("--methods")) {
    methods.clear();
    try {
      for (const std::string& key : split(*keys)) methods.push_back(eval::parse_method_key(key));
    } catch (const Error& e) {
      throw UsageError(e.what());
    }
    if (methods.empty()) throw UsageError("--methods needs at least one method");
  }
  const std::string output = args.get("--output").value_or("evaluation.md");

  eval::EvalRun run;
  run.pairs = eval::find_pairs(*dataset, sequences, pairs_text == "all");
  if (run.pairs.empty()) throw Error("no sequence found in '" + *dataset + "'");
  std::filesystem::path json_path(output);
  json_path.replace_extension(".json");
  std::vector<std::string> inputs;
  for (const eval::PairInput& pair : run.pairs)
    inputs.insert(inputs.end(), {pair.path_a, pair.path_b, pair.truth_path});
  refuse_outputs_that_are_inputs({{"-o", output}, {"-o (its data)", json_path.string()}}, inputs);
  run.methods = methods;
  run.matcher = std::string(to_string(settings.match.kind));
  run.timing_rounds = settings.timing_repeats;
  cv::setNumThreads(1);  // per-core times for every row

  const auto start = std::chrono::steady_clock::now();
  Progress progress("eval", static_cast<int>(run.pairs.size() * run.methods.size()));
  std::string loaded_a;
  GrayImage image_a;
  for (const eval::PairInput& pair : run.pairs) {
    if (pair.path_a != loaded_a) {
      image_a = read_image_reporting(pair.path_a, ExtractorOptions{}.max_image_pixels);
      loaded_a = pair.path_a;
    }
    const GrayImage image_b =
        read_image_reporting(pair.path_b, ExtractorOptions{}.max_image_pixels);
    std::vector<eval::PairResult> row;
    for (eval::Method method : run.methods) {
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

  const std::filesystem::path report_path(output);
  const std::string plots_name = report_path.stem().string() + "_plots";
  const std::filesystem::path plots_folder = report_path.parent_path() / plots_name;
  if (!report_path.parent_path().empty())
    std::filesystem::create_directories(report_path.parent_path());
  const std::vector<std::string> plots = eval::write_plots(run, plots_folder.string());
  std::string hand_written;  // kept from the report this one replaces
  if (std::ifstream previous{output}) {
    const std::string text((std::istreambuf_iterator<char>(previous)),
                           std::istreambuf_iterator<char>());
    hand_written = eval::hand_written_section(text);
  }
  std::string report = eval::markdown_report(run, plots_name);
  if (!hand_written.empty()) report += "\n" + hand_written;
  io::write_file_atomically(output, report);
  io::write_file_atomically(json_path.string(), eval::json_report(run));
  std::printf(
      "evaluated %zu pairs x %zu methods in %.0f s\nreport: %s\ndata: %s\nplots: %s/ (%zu)\n",
      run.pairs.size(), run.methods.size(), run.seconds, output.c_str(), json_path.string().c_str(),
      plots_folder.string().c_str(), plots.size());
  return 0;
}

}  // namespace aief::cli

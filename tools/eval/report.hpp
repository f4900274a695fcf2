#pragma once
// The evaluation report: the paper's four tables beside its figures, ground-truth metrics per
// sequence, the quality targets, as markdown and JSON, and a PNG plot per sequence.
#include <string>
#include <vector>

#include "tools/eval/dataset.hpp"
#include "tools/eval/methods.hpp"

namespace aief::eval {

struct EvalRun {
  std::vector<PairInput> pairs;
  std::vector<Method> methods;
  std::vector<std::vector<PairResult>> results;  // [pair][method]
  std::string matcher;
  double seconds = 0;
  int timing_rounds = 0;  // interleaved rounds per extraction time (timing.hpp)
  MachineLoad load;       // while timing
};

// The sequences of the run's pairs, in the order they first appear.
std::vector<std::string> sequences_of(const EvalRun& run);

// The markdown report (tools/eval/markdown_report.cpp): the paper's tables beside its figures,
// the ground-truth tables, the thresholds and the quality targets, links to the plots in
// `plot_folder_relative` (none if "").
std::string markdown_report(const EvalRun& run, const std::string& plot_folder_relative);

// A report may end with a hand-written section (docs/evaluation.md keeps its measurements there):
// the line kHandWrittenMarker and everything after it. Regenerating keeps it.
inline constexpr const char* kHandWrittenMarker =
    "<!-- hand-written below: aief eval keeps this line and all after it -->";
// The hand-written section of a previous report, from its marker to the end ("" without one).
std::string hand_written_section(const std::string& previous_report);
std::string json_report(const EvalRun& run);
// The hard families' tables (tools/eval/family_report.cpp): MMA at 1, 2 and 3 px, homography
// success and correct matches per pair by family and method, when every sequence is named
// FAMILY-IMAGE; "" otherwise.
std::string family_tables(const EvalRun& run);
// One PNG per sequence in `folder`: correct matches and accuracy against the pair index.
std::vector<std::string> write_plots(const EvalRun& run, const std::string& folder);

// Where write_reports put the report, its data and its plots.
struct ReportFiles {
  std::string markdown, json, plot_folder;
  std::vector<std::string> plots;
};
// The markdown report at `markdown_path` (keeping the hand-written section of the report it
// replaces), the JSON beside it (REPORT.json) and a plot per sequence in REPORT_plots/, each
// written atomically.
ReportFiles write_reports(const EvalRun& run, const std::string& markdown_path);

}  // namespace aief::eval

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
};

std::string markdown_report(const EvalRun& run, const std::string& plot_folder_relative);
std::string json_report(const EvalRun& run);
// One PNG per sequence in `folder`: correct matches and accuracy against the pair index.
std::vector<std::string> write_plots(const EvalRun& run, const std::string& folder);

}  // namespace aief::eval

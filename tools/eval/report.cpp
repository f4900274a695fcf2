// The JSON report and the plots of aief eval; the markdown is tools/eval/markdown_report.cpp.
#include "tools/eval/report.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/json_writer.hpp"
#include "io/plot.hpp"
#include "io/temporary_files.hpp"

namespace aief::eval {

std::vector<std::string> sequences_of(const EvalRun& run) {
  std::vector<std::string> out;
  for (const PairInput& p : run.pairs)
    if (std::find(out.begin(), out.end(), p.sequence) == out.end()) out.push_back(p.sequence);
  return out;
}

std::string hand_written_section(const std::string& previous_report) {
  const std::size_t at = previous_report.find(kHandWrittenMarker);
  return at == std::string::npos ? std::string() : previous_report.substr(at);
}

namespace {

// One row's measures on one pair, as a JSON object: PairResult's field list (methods.hpp).
void write_pair_result(io::JsonWriter& json, const PairResult& r) {
  json.begin_object();
  io::for_each_field(r, [&](std::string_view key, const auto& value) { json.field(key, value); });
  json.end_object();
}

}  // namespace

std::string json_report(const EvalRun& run) {
  std::ostringstream out;
  io::JsonWriter json(out);
  json.set_newline_depth(3);
  json.begin_object();
  json.field("matcher", run.matcher)
      .field("seconds", run.seconds)
      .field("timing_rounds", run.timing_rounds);
  json.field("load_average_lowest", run.load.lowest)
      .field("load_average_highest", run.load.highest);
  json.key("pairs").begin_array();
  for (std::size_t p = 0; p < run.pairs.size(); ++p) {
    json.begin_object()
        .field("sequence", run.pairs[p].sequence)
        .field("pair", "1-" + std::to_string(run.pairs[p].target));
    json.key("methods").begin_object();
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      json.key(method_key(run.methods[m]));
      write_pair_result(json, run.results[p][m]);
    }
    json.end_object().end_object();
  }
  json.end_array().end_object();
  return out.str();
}

std::vector<std::string> write_plots(const EvalRun& run, const std::string& folder) {
  std::filesystem::create_directories(folder);
  std::vector<std::string> written;
  for (const std::string& s : sequences_of(run)) {
    io::Plot plot;
    plot.title = s + ": img1 -> imgN";
    plot.x_label = "N, the target image of img1 -> imgN (the transformation grows with N)";
    io::PlotPanel correct{"correct matches (count; within 3 px of the true homography)", {}},
        accuracy{"matching accuracy (% of putative matches)", {}};
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      io::PlotSeries c{method_name(run.methods[m]), {}, {}}, a{c.label, {}, {}};
      for (std::size_t p = 0; p < run.pairs.size(); ++p) {
        if (run.pairs[p].sequence != s) continue;
        c.x.push_back(run.pairs[p].target);
        a.x.push_back(run.pairs[p].target);
        c.y.push_back(run.results[p][m].correct);
        a.y.push_back(100 * run.results[p][m].accuracy);
      }
      correct.series.push_back(c);
      accuracy.series.push_back(a);
    }
    plot.panels = {correct, accuracy};
    const std::string path = (std::filesystem::path(folder) / (s + ".png")).string();
    io::write_plot_png(path, plot);
    written.push_back(path);
  }
  return written;
}

ReportFiles write_reports(const EvalRun& run, const std::string& markdown_path) {
  const std::filesystem::path report_path(markdown_path);
  ReportFiles files;
  files.markdown = markdown_path;
  files.json = std::filesystem::path(report_path).replace_extension(".json").string();
  const std::string plots_name = report_path.stem().string() + "_plots";
  files.plot_folder = (report_path.parent_path() / plots_name).string();
  if (!report_path.parent_path().empty())
    std::filesystem::create_directories(report_path.parent_path());
  files.plots = write_plots(run, files.plot_folder);
  std::string hand_written;  // kept from the report this one replaces
  if (std::ifstream previous{markdown_path}) {
    const std::string text((std::istreambuf_iterator<char>(previous)),
                           std::istreambuf_iterator<char>());
    hand_written = hand_written_section(text);
  }
  std::string report = markdown_report(run, plots_name);
  if (!hand_written.empty()) report += "\n" + hand_written;
  io::write_file_atomically(files.markdown, report);
  io::write_file_atomically(files.json, json_report(run));
  return files;
}

}  // namespace aief::eval

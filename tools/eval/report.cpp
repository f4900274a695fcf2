// The JSON report and the plots of aief eval; the markdown is tools/eval/markdown_report.cpp.
#include "tools/eval/report.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "io/json_writer.hpp"
#include "io/plot.hpp"

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

// One row's measures on one pair, as a JSON object.
void write_pair_result(io::JsonWriter& json, const PairResult& r) {
  json.begin_object();
  json.field("keypoints_a", r.keypoints_a)
      .field("keypoints_b", r.keypoints_b)
      .field("putative", r.putative);
  json.field("inliers", r.inliers)
      .field("cmr", r.cmr)
      .field("correct", r.correct)
      .field("accuracy", r.accuracy);
  json.field("corner_error", r.corner_error)
      .field("homography_ok", r.homography_ok)
      .field("extract_ms", r.extract_ms);
  json.field("extract_min_ms", r.extract_min_ms).field("extract_max_ms", r.extract_max_ms);
  json.field("extract_wall_ms", r.extract_wall_ms);
  json.field("sweep_ms", r.sweep_ms)
      .field("threshold", r.threshold)
      .field("repeatability", r.repeatability);
  json.field("spread", r.spread).end_object();
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

}  // namespace aief::eval

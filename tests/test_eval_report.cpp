// aief eval's report, pinned byte for byte: the markdown (docs/evaluation.md is one), the JSON and
// the plots of every row on the bundled pairs. The times, which vary from run to run, are set to
// fixed figures; everything else is measured as `aief eval` measures it (cv::ORB and cv::SIFT rows:
// the OpenCV of scripts/setup).
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "tests/features_hash.hpp"
#include "tests/field_count.hpp"
#include "tests/test_support.hpp"
#include "tools/eval/dataset.hpp"
#include "tools/eval/methods.hpp"
#include "tools/eval/report.hpp"

namespace aief::eval {
namespace {

std::uint64_t hash_of(const std::string& text) {
  test::Fnv1a hash;
  hash.add(text.data(), text.size());
  return hash.value();
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every row on img1 -> img2 of the bundled sequences, times fixed.
EvalRun bundled_run() {
  EvalRun run;
  run.pairs = find_pairs(AIEF_SAMPLE_DIR, {"graf", "leuven", "boat"}, false);
  run.methods = kAllMethods;
  run.matcher = "mutual";
  run.seconds = 42;
  run.timing_rounds = 5;
  // run.load stays unsampled: the note on the load names this machine's hardware threads.
  cv::setNumThreads(1);
  const EvalSettings settings;
  for (std::size_t p = 0; p < run.pairs.size(); ++p) {
    const PairInput& pair = run.pairs[p];
    const cv::Mat a = test::load_sample_gray(pair.sequence, "img1.png");
    const cv::Mat b = test::load_sample_gray(pair.sequence, "img2.png");
    std::vector<PairResult> row;
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      PairResult r = run_method(run.methods[m], a, b, pair.truth, settings);
      r.extract_ms = 2.0 + 0.5 * static_cast<double>(m) + 0.125 * static_cast<double>(p);
      r.extract_min_ms = r.extract_ms - 0.25;
      r.extract_max_ms = r.extract_ms + 0.75;
      r.extract_wall_ms = r.extract_ms + 0.5;
      r.sweep_ms = r.sweep_ms > 0 ? 30.0 + static_cast<double>(p) : 0.0;
      row.push_back(r);
    }
    run.results.push_back(row);
  }
  return run;
}

// A run with only some of the rows: the sections that need a missing row are left out.
EvalRun with_rows(const EvalRun& full, const std::vector<std::size_t>& rows) {
  EvalRun run = full;
  run.methods.clear();
  for (std::size_t m : rows) run.methods.push_back(full.methods[m]);
  for (std::size_t p = 0; p < full.results.size(); ++p) {
    run.results[p].clear();
    for (std::size_t m : rows) run.results[p].push_back(full.results[p][m]);
  }
  return run;
}

TEST(EvalReport, MarkdownJsonAndPlotsOfTheBundledPairsArePinned) {
  const EvalRun run = bundled_run();
  ASSERT_EQ(run.pairs.size(), 3u);
  ASSERT_EQ(run.methods.size(), 10u);
  const std::string markdown = markdown_report(run, "evaluation_plots");
  EXPECT_EQ(markdown.find("# aief evaluation"), 0u);
  EXPECT_NE(markdown.find("| MMA@1px | MMA@2px | MMA@3px |"), std::string::npos);
  for (const std::vector<PairResult>& row : run.results)
    for (const PairResult& r : row) {  // the shares within 1, 2 and 3 px, each within the next
      EXPECT_LE(r.accuracy_1px, r.accuracy_2px);
      EXPECT_LE(r.accuracy_2px, r.accuracy);
    }
  EXPECT_EQ(hash_of(markdown), 5283372749901025846ull) << markdown;
  EXPECT_EQ(hash_of(json_report(run)), 3281205350881467455ull) << json_report(run);
  const test::TempFolder folder("aief_eval_report");
  const std::vector<std::string> plots = write_plots(run, folder.file("plots"));
  ASSERT_EQ(plots.size(), 3u);
  std::string all_plots;
  for (const std::string& path : plots) all_plots += bytes_of(path);
  EXPECT_EQ(hash_of(all_plots), 16712150332293087105ull);

  // Without the automatic, the adaptive paper and cv::ORB rows (no F table, no targets); and
  // without the swept row (the targets, no F table), no plots folder.
  const std::string fewer = markdown_report(with_rows(run, {0, 1, 4, 7}), "");
  EXPECT_EQ(hash_of(fewer), 9286336670702349261ull) << fewer;
  const std::string no_sweep = markdown_report(with_rows(run, {0, 3, 5, 6}), "plots");
  EXPECT_EQ(hash_of(no_sweep), 1347553882039833632ull) << no_sweep;
}

// One row on one pair, measured by hand: what write_reports and the record tests need.
EvalRun one_row_run() {
  EvalRun run;
  run.pairs = {{"graf", 2, "img1.png", "img2.png", "H1to2p", {1, 0, 0, 0, 1, 0, 0, 0, 1}}};
  run.methods = {kAllMethods.front()};
  run.matcher = "mutual";
  PairResult r;
  r.keypoints_a = 10;
  r.putative = 4;
  r.correct = 3;
  r.accuracy = 0.75;
  run.results = {{r}};
  return run;
}

// The family tables give MMA at 1, 2 and 3 px: the mean over a family's pairs of each share.
TEST(EvalReport, FamilyTablesGiveMmaAtOneTwoAndThreePixels) {
  EvalRun run;
  run.pairs = {{"blur-a", 2, "", "", "", {1, 0, 0, 0, 1, 0, 0, 0, 1}},
               {"blur-a", 3, "", "", "", {1, 0, 0, 0, 1, 0, 0, 0, 1}}};
  run.methods = {kAllMethods.front()};
  PairResult first, second;
  first.accuracy_1px = 0.25, first.accuracy_2px = 0.5, first.accuracy = 0.75;
  second.accuracy_1px = 0.35, second.accuracy_2px = 0.6, second.accuracy = 0.85;
  run.results = {{first}, {second}};
  const std::string tables = family_tables(run);
  const auto row_after = [&](const std::string& title) {
    const std::size_t at = tables.find("### " + title);
    EXPECT_NE(at, std::string::npos) << tables;
    const std::size_t row = tables.find("| " + method_name(run.methods[0]) + " |", at);
    return tables.substr(row, tables.find('\n', row) - row);
  };
  const std::string name = "| " + method_name(run.methods[0]) + " |";
  EXPECT_EQ(row_after("MMA@1px (%)"), name + " 30.0 | 30.0 |");
  EXPECT_EQ(row_after("MMA@2px (%)"), name + " 55.0 | 55.0 |");
  EXPECT_EQ(row_after("MMA@3px (%)"), name + " 80.0 | 80.0 | 0.00 |");
}

TEST(EvalReport, TheJsonRowIsPairResultsFieldListEveryFieldInOrder) {
  EXPECT_EQ(io::field_list_size<PairResult>(), test::field_count<PairResult>())
      << "a field of PairResult without its entry in RecordFields<PairResult> (methods.hpp)";
  const std::string json = json_report(one_row_run());
  std::size_t at = json.find("\"orbslam2\"");
  ASSERT_NE(at, std::string::npos) << json;
  for (std::string_view key : io::field_keys<PairResult>()) {
    const std::size_t next = json.find("\"" + std::string(key) + "\":", at);
    ASSERT_NE(next, std::string::npos) << key << " is not in its place in\n" << json;
    at = next;
  }
}

TEST(EvalReport, WriteReportsPutsTheJsonAndPlotsBesideAndKeepsTheHandWrittenSection) {
  const test::TempFolder folder("aief_eval_write_reports");
  const std::string markdown = folder.file("out/report.md");
  const EvalRun run = one_row_run();
  ReportFiles files = write_reports(run, markdown);
  EXPECT_EQ(files.markdown, markdown);
  EXPECT_EQ(files.json, folder.file("out/report.json"));
  EXPECT_EQ(files.plot_folder, folder.file("out/report_plots"));
  ASSERT_EQ(files.plots.size(), 1u);
  EXPECT_EQ(bytes_of(files.json), json_report(run));
  EXPECT_EQ(bytes_of(markdown), markdown_report(run, "report_plots"));

  const std::string kept = std::string(kHandWrittenMarker) + "\nmeasured by hand\n";
  { std::ofstream(markdown, std::ios::app) << "\n" << kept; }
  files = write_reports(run, markdown);
  EXPECT_EQ(bytes_of(markdown), markdown_report(run, "report_plots") + "\n" + kept);
}

}  // namespace
}  // namespace aief::eval

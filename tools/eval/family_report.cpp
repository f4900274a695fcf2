// The hard families' tables of the report: sequences named FAMILY-IMAGE
// (scripts/make_synthetic_pairs.py --families) grouped by family, every method side by side.
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tools/eval/report.hpp"

namespace aief::eval {

namespace {

std::string family_of(const std::string& sequence) {
  const std::size_t dash = sequence.find('-');
  return dash == std::string::npos ? std::string() : sequence.substr(0, dash);
}

std::string fixed(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// One method's sums over a family's pairs.
struct FamilyFigures {
  int pairs = 0, homographies = 0, correct = 0;
  double accuracy = 0, accuracy_1px = 0, accuracy_2px = 0, time_ms = 0;
};

}  // namespace

std::string family_tables(const EvalRun& run) {
  std::vector<std::string> families;  // in the order they first appear
  for (const PairInput& pair : run.pairs) {
    const std::string family = family_of(pair.sequence);
    if (family.empty()) return "";  // not a run over the hard families
    bool known = false;
    for (const std::string& f : families) known = known || f == family;
    if (!known) families.push_back(family);
  }
  if (families.empty()) return "";
  // [method][family], the last family column the whole run.
  std::vector<std::vector<FamilyFigures>> figures(run.methods.size(),
                                                  std::vector<FamilyFigures>(families.size() + 1));
  for (std::size_t p = 0; p < run.pairs.size(); ++p) {
    std::size_t f = 0;
    while (families[f] != family_of(run.pairs[p].sequence)) ++f;
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      const PairResult& r = run.results[p][m];
      for (FamilyFigures* sum : {&figures[m][f], &figures[m][families.size()]}) {
        ++sum->pairs;
        sum->homographies += r.homography_ok ? 1 : 0;
        sum->correct += r.correct;
        sum->accuracy += r.accuracy;
        sum->accuracy_1px += r.accuracy_1px;
        sum->accuracy_2px += r.accuracy_2px;
        sum->time_ms += r.extract_ms;
      }
    }
  }
  std::ostringstream md;
  md << "\n## Hard families\n\nSequences FAMILY-IMAGE (scripts/make_synthetic_pairs.py "
        "--families), img1 -> img2..6 of each, grouped by family. MMA@1px, @2px, @3px: the mean "
        "over the pairs of correct / putative matches (correct: within 1, 2, 3 px under the true "
        "homography); "
        "homography success: mean corner error of our RANSAC model below 5 px; correct matches "
        "per pair; time: extraction + description of img1, one thread, CPU ms (mean of the "
        "per-pair medians).\n";
  const auto table = [&](const std::string& title, auto cell, bool with_time) {
    md << "\n### " << title << "\n\n| method |";
    for (const std::string& f : families) md << ' ' << f << " |";
    md << " all |" << (with_time ? " time ms |" : "") << "\n|---|";
    for (std::size_t i = 0; i < families.size() + 1 + (with_time ? 1 : 0); ++i) md << "---|";
    md << '\n';
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      md << "| " << method_name(run.methods[m]) << " |";
      for (const FamilyFigures& sum : figures[m]) md << ' ' << cell(sum) << " |";
      const FamilyFigures& all = figures[m].back();
      if (with_time) md << ' ' << fixed("%.2f", all.pairs ? all.time_ms / all.pairs : 0.0) << " |";
      md << '\n';
    }
  };
  const auto mma = [&](const char* title, double FamilyFigures::*share, bool with_time) {
    table(
        title,
        [share](const FamilyFigures& s) {
          return fixed("%.1f", s.pairs ? 100 * (s.*share) / s.pairs : 0.0);
        },
        with_time);
  };
  mma("MMA@1px (%)", &FamilyFigures::accuracy_1px, false);
  mma("MMA@2px (%)", &FamilyFigures::accuracy_2px, false);
  table(
      "MMA@3px (%)",
      [](const FamilyFigures& s) {
        return fixed("%.1f", s.pairs ? 100 * s.accuracy / s.pairs : 0.0);
      },
      true);
  table(
      "Homography success (% of pairs)",
      [](const FamilyFigures& s) {
        return fixed("%.0f", s.pairs ? 100.0 * s.homographies / s.pairs : 0.0);
      },
      false);
  table(
      "Correct matches per pair",
      [](const FamilyFigures& s) {
        return fixed("%.0f", s.pairs ? static_cast<double>(s.correct) / s.pairs : 0.0);
      },
      false);
  return md.str();
}

}  // namespace aief::eval

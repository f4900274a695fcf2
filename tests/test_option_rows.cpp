// A malformed option row is refused (core/options/malformed_row.hpp): each kind of bad row is
// found, with its key, by the check every table's file runs as it compiles
// (AIEF_CHECK_OPTION_ROWS), and the real tables pass it. That a bad row stops the build is the
// CTests malformed_option_row_* (tests/compile_fail/malformed_option_row.cpp).
#include <string_view>

#include <gtest/gtest.h>

#include "aief/adapt.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"
#include "core/options/malformed_row.hpp"
#include "core/options/option_access.hpp"
#include "core/options/option_table.hpp"

namespace aief::option_table {
namespace {

using O = ExtractorOptions;  // AIEF_OPTION_ROW's struct

constexpr OptionRow kFeatures = {
    AIEF_OPTION_ROW(n_features),
    .cli_flag = "--n-features",
    .python_keyword = "n_features",
    .python_position = 1,
    .yaml_key = "ORBextractor.nFeatures",
    .help = "keypoints wanted",
    .low = 1,
    .high = 1000,
};
constexpr OptionRow kLevels = {
    AIEF_OPTION_ROW(n_levels),
    .cli_flag = "--n-levels",
    .python_keyword = "n_levels",
    .python_position = 2,
    .old_cli_flag = "--levels",
    .help = "pyramid levels",
    .low = 1,
    .high = 32,
    .per_mode = {.aief = "",
                 .aief_paper = "",
                 .orbslam2 = "",
                 .quadtree_entropy = "",
                 .faithful = "",
                 .quality = "18"},
};

constexpr OptionRow kGood[] = {kFeatures, kLevels};
AIEF_CHECK_OPTION_ROWS(kGood);

// kLevels changed by `change`.
template <class Change>
constexpr OptionRow changed(Change change) {
  OptionRow row = kLevels;
  change(row);
  return row;
}

constexpr OptionRow kDuplicateKey[] = {kFeatures, {AIEF_OPTION_ROW(n_features), .help = "again"}};
constexpr OptionRow kLowAboveHigh[] = {kFeatures, changed([](OptionRow& r) { r.low = 33; })};
constexpr OptionRow kModeLeftOut[] = {
    kFeatures, changed([](OptionRow& r) {
      r.per_mode = {.aief = "", .aief_paper = "", .orbslam2 = "", .faithful = "", .quality = "18"};
    })};
constexpr OptionRow kNewlineInHelp[] = {kFeatures,
                                        changed([](OptionRow& r) { r.help = "pyramid\nlevels"; })};
constexpr OptionRow kNoKey[] = {kFeatures, changed([](OptionRow& r) { r.key = ""; })};
constexpr OptionRow kNoHelp[] = {kFeatures, changed([](OptionRow& r) { r.help = ""; })};
constexpr OptionRow kFlagTwice[] = {kFeatures,
                                    changed([](OptionRow& r) { r.old_cli_flag = "--n-features"; })};
constexpr OptionRow kKeywordTwice[] = {
    kFeatures, changed([](OptionRow& r) { r.python_keyword = "n_features"; })};
constexpr OptionRow kSettingsKeyTwice[] = {
    kFeatures, changed([](OptionRow& r) { r.old_yaml_key = "ORBextractor.nFeatures"; })};
constexpr OptionRow kPositionTwice[] = {kFeatures,
                                        changed([](OptionRow& r) { r.python_position = 1; })};
constexpr OptionRow kFlagWithoutDashes[] = {kFeatures,
                                            changed([](OptionRow& r) { r.cli_flag = "n-levels"; })};

// The check is a constant expression: the same answers at compile time.
static_assert(malformed_row(kDuplicateKey).problem == "a second row");
static_assert(malformed_row(kLowAboveHigh).problem == "low > high");
static_assert(!malformed_row(kModeLeftOut).empty());
static_assert(!malformed_row(kNewlineInHelp).empty());

TEST(OptionRows, AWellFormedTableHasNoProblem) {
  EXPECT_TRUE(malformed_row(kGood).empty()) << malformed_row(kGood).problem;
}

TEST(OptionRows, EachKindOfMalformedRowIsFoundWithItsKey) {
  struct Case {
    RowProblem found;
    std::string_view key, problem;
  };
  const Case cases[] = {
      {malformed_row(kDuplicateKey), "n_features", "a second row"},
      {malformed_row(kLowAboveHigh), "n_levels", "low > high"},
      {malformed_row(kModeLeftOut), "n_levels",
       "per_mode without a value for every mode (\"\" leaves the option as it was)"},
      {malformed_row(kNewlineInHelp), "n_levels",
       "a newline in its help or another text (--help is one line)"},
      {malformed_row(kNoKey), "", "a row without a key"},
      {malformed_row(kNoHelp), "n_levels", "no help"},
      {malformed_row(kFlagTwice), "n_features", "a CLI flag another row has"},
      {malformed_row(kKeywordTwice), "n_features", "a Python keyword another row has"},
      {malformed_row(kSettingsKeyTwice), "n_features", "a settings key another row has"},
      {malformed_row(kPositionTwice), "n_features", "a Python position another row has"},
      {malformed_row(kFlagWithoutDashes), "n_levels", "a CLI flag without --"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(c.found.problem, c.problem) << c.key;
    EXPECT_EQ(c.found.key, c.key) << c.problem;
  }
}

TEST(OptionRows, ATableWithoutModesRefusesPerMode) {
  using O = MatchOptions;
  constexpr Row<MatchOptions> rows[] = {
      {AIEF_OPTION_ROW(ratio), .help = "Lowe's ratio", .low = 0, .high = 1,
       .per_mode = {.aief = "0.8",
                    .aief_paper = "",
                    .orbslam2 = "",
                    .quadtree_entropy = "",
                    .faithful = "",
                    .quality = ""}},
  };
  EXPECT_EQ(malformed_row(rows).problem, "per_mode in a table without modes");
}

// The tables themselves (their files stop the build otherwise; here the key is printed).
TEST(OptionRows, EveryTableIsWellFormed) {
  const RowProblem problems[] = {
      malformed_row(rows_of<ExtractorOptions>()), malformed_row(rows_of<MatchOptions>()),
      malformed_row(rows_of<SweepOptions>()), malformed_row(rows_of<RansacOptions>())};
  for (const RowProblem& p : problems) EXPECT_TRUE(p.empty()) << p.key << ": " << p.problem;
}

}  // namespace
}  // namespace aief::option_table

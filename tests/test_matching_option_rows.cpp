// The option tables of matching, the sweep and RANSAC (core/options/matching_option_rows.cpp):
// every field is a row, every row with a flag reaches aief match / aief adapt and their --help,
// validate() is made from the rows, the matcher's names are read from their one name table, and the
// ratio rule
// (--ratio with --matcher ratio, mutual_ratio or guided only) holds. Before, these options were a
// second, hand-made system: MatcherKind's names written three times, the sweep's ranges twice,
// flags by hand.
#include <filesystem>
#include <limits>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"
#include "tests/field_count.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

namespace table = option_table;

using test::field_count;

template <class Options>
std::set<std::string_view> keys_of() {
  std::set<std::string_view> keys;
  for (const table::Row<Options>& row : table::rows_of<Options>()) {
    EXPECT_TRUE(row.is_field() && !row.help.empty() && !row.python_keyword.empty()) << row.key;
    EXPECT_TRUE(keys.insert(row.key).second) << row.key;
  }
  return keys;
}

TEST(MatchingOptionRows, EveryFieldIsARow) {
  EXPECT_EQ(keys_of<MatchOptions>().size(), field_count<MatchOptions>());
  EXPECT_EQ(keys_of<RansacOptions>().size(), field_count<RansacOptions>());
  // The sweep's own fields; its matcher and RANSAC options are their structs' rows.
  EXPECT_EQ(keys_of<SweepOptions>().size() + 2, field_count<SweepOptions>());
}

TEST(MatchingOptionRows, ValidateIsMadeFromTheRows) {
  const auto message = [](auto options) -> std::string {
    try {
      options.validate();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  MatchOptions match;
  match.ratio = 0;
  EXPECT_EQ(message(match), "ratio must be a number in (0, 1], got 0");
  match = {};
  match.max_distance = 257;
  EXPECT_EQ(message(match), "max_distance must be an integer in [0, 256], got 257");
  match = {};
  match.kind = static_cast<MatcherKind>(7);
  EXPECT_EQ(message(match), "kind has an unknown value");
  RansacOptions ransac;
  ransac.confidence = 1;
  EXPECT_EQ(message(ransac), "confidence must be a number in (0, 1), got 1");
  ransac = {};
  ransac.threshold_px = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message(ransac), "threshold_px must be a number > 0, got inf");
  SweepOptions sweep;
  sweep.step = 9;
  EXPECT_EQ(message(sweep), "step must be a number in [0.01, 8], got 9");
  sweep = {};
  sweep.match.ratio = 2;  // the nested structs are checked too
  EXPECT_EQ(message(sweep), "ratio must be a number in (0, 1], got 2");
  EXPECT_EQ(message(SweepOptions{}), "");
}

TEST(MatchingOptionRows, TheMatchersNamesAreOneTable) {
  for (const auto& name : option_names::Table<MatcherKind>::names) {
    EXPECT_EQ(to_string(name.value), name.name);
    EXPECT_EQ(parse_matcher_kind(name.name), name.value);
  }
  try {
    parse_matcher_kind("nearest");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(
        e.what(),
        "unknown matcher 'nearest' (expected mutual, ratio, paper, mutual_ratio or guided)");
  }
}

TEST(MatchingOptionRows, TheRatioGoesWithTheRatioMatcherOnly) {
  const table::Row<MatchOptions>& ratio = table::row_of<MatchOptions>("ratio");
  const table::Row<MatchOptions>& kind = table::row_of<MatchOptions>("kind");
  EXPECT_EQ(table::resolve_options<MatchOptions>(
                {{&ratio, "0.5", "--ratio"}, {&kind, "ratio", "--matcher"}}, table::FrontEnd::cli)
                .ratio,
            0.5);
  try {
    table::resolve_options<MatchOptions>({{&ratio, "0.5", "ratio"}}, table::FrontEnd::python);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "ratio applies to matcher ratio, mutual_ratio or guided only, not mutual");
  }
  // Each value the row lists lets it act (applies_with_value "ratio|mutual_ratio").
  EXPECT_EQ(
      table::resolve_options<MatchOptions>(
          {{&ratio, "0.6", "--ratio"}, {&kind, "mutual_ratio", "--matcher"}}, table::FrontEnd::cli)
          .ratio,
      0.6);
  EXPECT_TRUE(table::is_one_of("ratio|mutual_ratio", "mutual_ratio"));
  EXPECT_FALSE(table::is_one_of("ratio|mutual_ratio", "mutual"));
  EXPECT_FALSE(table::is_one_of("ratio|mutual_ratio", "ratio|mutual_ratio"));
  EXPECT_EQ(table::one_of_text("ratio|mutual_ratio"), "ratio or mutual_ratio");
  EXPECT_EQ(table::one_of_text("ratio|mutual_ratio|guided"), "ratio, mutual_ratio or guided");
}

test::CommandRun run_cli(const std::string& arguments) {
  return test::run_shell(std::string(AIEF_CLI_PATH) + " " + arguments);
}

template <class Options>
void expect_every_flag_in(const std::string& help) {
  for (const table::Row<Options>& row : table::rows_of<Options>())
    if (!row.cli_flag.empty()) {
      EXPECT_NE(help.find("  " + std::string(row.cli_flag) + " " + std::string(row.cli_value)),
                std::string::npos)
          << row.cli_flag;
    }
}

TEST(MatchingOptionRows, EveryFlagIsInItsCommandsHelp) {
  const test::CommandRun match = run_cli("match --help"), adapt = run_cli("adapt --help");
  ASSERT_EQ(match.status, 0);
  ASSERT_EQ(adapt.status, 0);
  expect_every_flag_in<MatchOptions>(match.output);
  expect_every_flag_in<MatchOptions>(adapt.output);
  expect_every_flag_in<SweepOptions>(adapt.output);
}

TEST(MatchingOptionRows, TheCommandsReadTheirFlagsByTheRows) {
  const std::string a = test::sample_path("graf", "img1.png");
  const test::CommandRun ratio = run_cli("match " + a + " " + a + " --ratio 0.7");
  EXPECT_EQ(ratio.status, 2);
  EXPECT_NE(ratio.output.find(
                "--ratio applies to --matcher ratio, mutual_ratio or guided only, not mutual"),
            std::string::npos)
      << ratio.output;
  const test::CommandRun step = run_cli("adapt " + a + " " + a + " --step 0");
  EXPECT_EQ(step.status, 2);
  EXPECT_NE(step.output.find("--step expects a number in [0.01, 8], got '0'"), std::string::npos)
      << step.output;
  const test::CommandRun inliers = run_cli("adapt " + a + " " + a + " --min-inliers 3");
  EXPECT_EQ(inliers.status, 2);
  EXPECT_NE(inliers.output.find("--min-inliers expects an integer in [4, 1000000], got '3'"),
            std::string::npos)
      << inliers.output;
}

// match --pairs matches a features file: the flags of extraction, the picture and the sweep do not
// apply. Before, --adaptive, --draw, --mode, --threshold and --levels were silently ignored.
TEST(MatchingOptionRows, MatchPairsRefusesTheFlagsThatDoNotApply) {
  const test::TempFolder folder("aief_match_pairs_flags");
  const std::string common = "match --pairs " + folder.file("pairs.txt") + " --features-file " +
                             folder.file("f.h5") + " -o " + folder.file("m.h5");
  // A flag is named as it was given, the earlier spellings (CHANGELOG.md) too.
  for (const std::string& flag : std::vector<std::string>{
           "--adaptive", "--draw " + folder.file("d.png"), "--mode orbslam2",
           "--entropy-threshold 3", "--n-levels 4", "--threshold 3", "--levels 4"}) {
    const test::CommandRun r = run_cli(common + " " + flag);
    EXPECT_EQ(r.status, 2) << flag;
    const std::string name = flag.substr(0, flag.find(' '));
    EXPECT_NE(r.output.find("as they were extracted: " + name + " does not apply"),
              std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(folder.file("m.h5")));
}

}  // namespace
}  // namespace aief

namespace aief {
namespace {

// A matches file written before --epipolar-band existed records no epipolar_band_px: a resumed
// match --pairs keeps its pairs for every matcher but guided, where the band acts (before, every
// pair was matched again, "epipolar_band_px not recorded -> 1").
TEST(MatchingOptionRows, ARowThatActsInNeitherRecordIsNoDifference) {
  const option_table::RecordedOptions before = {
      {"kind", "mutual_ratio"}, {"ratio", "0.8"}, {"max_distance", "256"}};
  option_table::RecordedOptions now = before;
  now.emplace_back("epipolar_band_px", "1");
  EXPECT_TRUE(option_table::output_differences<MatchOptions>(before, now).empty());
  option_table::RecordedOptions guided_before = before, guided_now = now;
  guided_before[0].second = guided_now[0].second = "guided";
  const auto differences =
      option_table::output_differences<MatchOptions>(guided_before, guided_now);
  ASSERT_EQ(differences.size(), 1u);
  EXPECT_EQ(option_table::text_of(differences[0]), "epipolar_band_px not recorded -> 1");
  // One record where the band acts is enough: guided against mutual_ratio differs in both rows.
  EXPECT_EQ(option_table::output_differences<MatchOptions>(before, guided_now).size(), 2u);
}

}  // namespace
}  // namespace aief

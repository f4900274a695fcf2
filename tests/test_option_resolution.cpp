// Options as every front end reads them (core/options/option_table.hpp): the number syntax, the
// enum names, the version, and the one resolution rule (the mode first, the options given over it,
// conflicts refused, an option that cannot act refused naming what it needs). Every row reaching
// every front end: tests/test_option_table.cpp.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/version.hpp"
#include "core/options/acts_with.hpp"
#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"
#include "tests/cli_run.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

namespace table = option_table;

using test::CliResult;
using test::run_cli;

TEST(OptionTable, NumbersAreDecimalWithinTheRowsRange) {
  const auto error_of = [](std::string_view key, std::string_view text) -> std::string {
    try {
      table::parse_value(table::row(key), text, "--x");
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  // Hex was read as 16 by --threshold and --pool (std::stod), refused by --features (std::stoll).
  for (std::string_view key : {"entropy_threshold", "candidate_pool", "n_features", "scale_factor"})
    EXPECT_NE(error_of(key, "0x10"), "") << key;
  for (std::string_view text :
       {" 5", "5 ", "5.5.5", "1e", "e5", "+", "-", ".", "nan", "infinity", "1,5", "--5", "5f"})
    EXPECT_NE(error_of("entropy_threshold", text), "") << text;
  // 1e-320 (a subnormal) is inside [0, 64]; strtod's ERANGE refused it.
  EXPECT_EQ(error_of("entropy_threshold", "1e-320"), "");
  EXPECT_NE(error_of("entropy_threshold", "1e400"), "");
  // -0 is 0, never printed as -0.
  const table::OptionValue zero =
      table::parse_value(table::row("entropy_threshold"), "-0", "--threshold");
  EXPECT_FALSE(std::signbit(std::get<double>(zero)));
  for (std::string_view text : {"+5", "-0", ".5", "5.", "1E1", "2e+1", "3e-1"})
    EXPECT_EQ(error_of("entropy_threshold", text), "") << text;
  EXPECT_EQ(error_of("n_features", "+500"), "");
  EXPECT_NE(error_of("n_features", "5e2"), "");
  EXPECT_NE(error_of("n_features", "99999999999999999999"), "");
  EXPECT_NE(error_of("n_features", "1000001")
                .find("--x expects an integer in [1, 1000000], got '1000001'"),
            std::string::npos);
  EXPECT_NE(error_of("scale_factor", "1").find("--x expects a number in (1, 4], got '1'"),
            std::string::npos);
  EXPECT_NE(error_of("entropy_threshold", "x").find("a number in [0, 64], auto or carried"),
            std::string::npos);
  EXPECT_NE(error_of("candidate_pool", "0.5").find("a number >= 1, inf or off"), std::string::npos);
}

TEST(OptionTable, TheCliReadsNumbersByTheTable) {
  const std::string image = test::sample_path("boat", "img1.png");
  for (const char* flags : {"--threshold 0x10", "--pool 0x10", "--features 0x10", "--scale 0x1.8p0",
                            "--threshold inf"}) {
    const CliResult r = run_cli("extract " + image + " " + flags);
    EXPECT_EQ(r.status, 2) << flags << "\n" << r.output;
  }
  const CliResult tiny = run_cli("extract " + image + " --threshold 1e-320");
  EXPECT_EQ(tiny.status, 0) << tiny.output;
  const CliResult zero = run_cli("extract " + image + " --threshold -0");
  EXPECT_EQ(zero.status, 0) << zero.output;
  EXPECT_EQ(zero.output.find("-0"), std::string::npos) << zero.output;
}

TEST(OptionTable, VersionIsTheBuildsAndTakesNoArgument) {
  const CliResult version = run_cli("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output, std::string("aief ") + kVersionString + "\n");
  const CliResult extra = run_cli("--version extra");
  EXPECT_EQ(extra.status, 2) << extra.output;
  EXPECT_NE(extra.output.find("--version takes no argument"), std::string::npos) << extra.output;
}

ExtractorOptions resolve(const std::vector<std::pair<std::string_view, std::string>>& given) {
  std::vector<table::GivenOption> list;
  for (const auto& [key, text] : given) list.push_back({&table::row(key), text, std::string(key)});
  return table::resolve_options(list);
}

std::string resolve_error(const std::vector<std::pair<std::string_view, std::string>>& given) {
  try {
    resolve(given);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(OptionTable, TheModeSetsTheOptionsGivenOverrideConflictsAreRefused) {
  // Given options apply after the mode, whatever the order they came in.
  EXPECT_EQ(resolve({{"entropy", "off"}}).entropy, EntropyMeasure::off);
  EXPECT_EQ(resolve({{"entropy", "off"}, {"mode", "aief-paper"}}).entropy, EntropyMeasure::off);
  EXPECT_EQ(resolve({{"coordinates", "pixel-centre"}, {"mode", "orbslam2"}}).coordinates,
            CoordinateMap::pixel_centre);
  EXPECT_EQ(resolve({{"mode", "quadtree-entropy"}, {"entropy", "intensity"}}).distribution,
            Distribution::quadtree);
  EXPECT_TRUE(resolve({{"entropy_threshold", "auto"}}).auto_threshold);
  EXPECT_TRUE(std::isinf(resolve({{"candidate_pool", "off"}}).candidate_pool));
  // The mode's definition cannot be overridden; F cannot apply without the mask.
  EXPECT_NE(resolve_error({{"mode", "orbslam2"}, {"entropy", "histogram"}})
                .find("mode orbslam2 means entropy off"),
            std::string::npos);
  EXPECT_EQ(resolve_error({{"mode", "orbslam2"}, {"entropy", "off"}}), "");
  EXPECT_NE(resolve_error({{"entropy", "off"}, {"entropy_threshold", "7"}})
                .find("which entropy off turns off"),
            std::string::npos);
  EXPECT_NE(resolve_error({{"mode", "orbslam2"}, {"entropy_threshold", "auto"}})
                .find("which mode orbslam2 turns off"),
            std::string::npos);
  // validate() still has the last word.
  EXPECT_NE(resolve_error({{"fast_threshold", "10"}, {"fast_min_threshold", "11"}})
                .find("fast_min_threshold"),
            std::string::npos);
  // options_for_mode is the same table.
  for (const auto& mode : option_names::Table<Mode>::names)
    EXPECT_EQ(table::record_of(resolve({{"mode", std::string(mode.name)}})),
              table::record_of(options_for_mode(mode.value)))
        << mode.name;
}

// Options that cannot act with the others were accepted and did nothing (--mode faithful
// --fast-threshold-from entropy gave faithful's bytes); now refused, naming what they need, in
// every front end (one rule: core/options/acts_with.hpp).
TEST(OptionTable, AnOptionThatCannotActIsRefusedNamingWhatItNeeds) {
  const auto refused = [](const std::vector<std::pair<std::string_view, std::string>>& given,
                          const std::string& says) {
    const std::string error = resolve_error(given);
    EXPECT_NE(error.find(says), std::string::npos) << "'" << error << "' lacks '" << says << "'";
  };
  refused({{"mode", "faithful"}, {"fast_threshold_from", "entropy"}},
          "fast_threshold_from entropy does nothing unless detection_cells blocks, and mode "
          "faithful makes it orbslam");
  refused({{"detection_cells", "orbslam"}, {"fast_threshold_from", "entropy"}},
          "detection_cells orbslam is given");
  refused({{"mode", "aief"}, {"quadtree_weight", "entropy"}},
          "does nothing unless distribution quadtree (modes orbslam2, quadtree-entropy, faithful)");
  refused({{"mode", "orbslam2"}, {"quadtree_weight", "entropy"}, {"quadtree_ties", "orbslam"}},
          "quadtree_ties orbslam does nothing unless quadtree_weight none");
  refused({{"quadtree_ties", "orbslam"}}, "does nothing unless distribution quadtree");
  refused({{"carry_every", "10"}}, "does nothing unless carried_threshold on");
  refused({{"mode", "faithful"}, {"scale_selection", "extrema"}},
          "scale_selection extrema does nothing unless detection_cells blocks, and mode "
          "faithful makes it orbslam");
  refused({{"mode", "orbslam2"}, {"candidate_pool", "2"}},
          "does nothing unless distribution proportional");
  refused({{"auto_requires_two_classes", "off"}}, "does nothing unless auto_threshold on");
  refused({{"auto_skips_uniform_blocks", "count"}}, "does nothing unless auto_threshold on");
  // Where they act they are taken; a value the mode sets is no request.
  EXPECT_EQ(resolve_error({{"mode", "faithful"}, {"quadtree_weight", "entropy"}}), "");
  EXPECT_EQ(resolve_error({{"mode", "orbslam2"}, {"fast_threshold_from", "entropy"}}), "");
  EXPECT_EQ(resolve_error({{"entropy_threshold", "carried"}, {"carry_every", "10"}}), "");
  EXPECT_EQ(resolve_error({{"entropy_threshold", "auto"}, {"auto_requires_two_classes", "off"}}),
            "");
  EXPECT_EQ(resolve_error({{"mode", "faithful"}, {"fast_threshold_from", "none"}}), "");
  EXPECT_EQ(resolve_error({{"mode", "orbslam2"}, {"candidate_pool", "inf"}}), "");
  // Every mode's options given whole without the mode (Extractor(**extractor.options)) make the
  // same options, faithful with the weighted quadtree too.
  std::vector<ExtractorOptions> presets;
  for (const auto& mode : option_names::Table<Mode>::names)
    presets.push_back(options_for_mode(mode.value));
  presets.push_back(options_for_mode(Mode::faithful));
  presets.back().quadtree_weight = QuadtreeWeight::entropy;
  for (const ExtractorOptions& preset : presets) {
    std::vector<std::pair<std::string_view, std::string>> whole;
    for (const auto& [key, value] : table::record_of(preset))
      whole.emplace_back(key, table::text_of(table::row(key), value));
    EXPECT_EQ(resolve_error(whole), "");
    if (resolve_error(whole).empty()) {
      EXPECT_EQ(table::record_of(resolve(whole)), table::record_of(preset));
    }
  }
  // validate() refuses what no preset holds, however the options were made (C++, Feature2D).
  ExtractorOptions faithful = options_for_mode(Mode::faithful);
  faithful.fast_threshold_from = FastThresholdFrom::entropy;
  EXPECT_THROW(faithful.validate(), Error);
  ExtractorOptions weighted;
  weighted.quadtree_weight = QuadtreeWeight::entropy;
  EXPECT_THROW(weighted.validate(), Error);
  ExtractorOptions carry;  // a number carried along in a struct: refused only when given
  carry.carry_every = 5;
  EXPECT_NO_THROW(carry.validate());
  // The adaptive sweep chooses F itself, without the fallback.
  const auto sweep_error = [](std::string_view key, const std::string& text) {
    try {
      table::resolve_options({{&table::row(key), text, std::string(key)}}, table::Use::sweep);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(sweep_error("entropy_threshold", "7").find("does nothing in the adaptive sweep"),
            std::string::npos);
  EXPECT_NE(sweep_error("starvation_guard", "frame").find("does nothing in the adaptive sweep"),
            std::string::npos);
  EXPECT_EQ(sweep_error("mode", "aief-paper"), "");
  // A mode's every value given (Extractor(**e.options)) is the mode: its frame-wide guard is no
  // request to the sweep either.
  std::vector<table::GivenOption> paper_record;
  for (const auto& [key, value] : table::record_of(options_for_mode(Mode::aief_paper)))
    paper_record.push_back(
        {&table::row(key), table::text_of(table::row(key), value), std::string(key)});
  EXPECT_NO_THROW(table::resolve_options(paper_record, table::Use::sweep));
  // aief eval turns the automatic F on per row: its options are taken without it.
  EXPECT_NO_THROW(table::resolve_options(
      {{&table::row("auto_requires_two_classes"), "off", "--auto-two-classes"}},
      table::Use::evaluation));
  // The CLI says it, exit 2.
  const std::string a = test::sample_path("graf", "img1.png"),
                    b = test::sample_path("graf", "img2.png");
  for (const std::string& arguments :
       {"extract " + a + " --mode faithful --fast-threshold-from entropy",
        "extract " + a + " --detection-cells orbslam --fast-threshold-from entropy",
        "extract " + a + " --mode aief --quadtree-weight entropy",
        "extract " + a + " --mode orbslam2 --quadtree-weight entropy --quadtree-ties orbslam",
        "extract " + a + " --carry-every 10", "match " + a + " " + b + " --adaptive --threshold 7",
        "adapt " + a + " " + b + " --threshold 7"}) {
    const CliResult r = run_cli(arguments);
    EXPECT_EQ(r.status, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find("does nothing"), std::string::npos) << arguments << "\n" << r.output;
  }
}

// A record holds numbers at 17 digits; a difference shows them by their shortest text (was:
// "ratio 0.69999999999999996 -> 0.80000000000000004").
TEST(OptionTable, DifferencesShowNumbersByTheirShortestText) {
  EXPECT_EQ(table::text_of(
                table::OptionDifference{"ratio", "0.69999999999999996", "0.80000000000000004"}),
            "ratio 0.7 -> 0.8");
  EXPECT_EQ(table::text_of(table::OptionDifference{"n_features", "500", "3000"}),
            "n_features 500 -> 3000");
  EXPECT_EQ(table::text_of(table::OptionDifference{"candidate_pool", "1.25", "inf"}),
            "candidate_pool 1.25 -> inf");
  EXPECT_EQ(table::text_of(table::OptionDifference{"mode", "not recorded", "quadtree"}),
            "mode not recorded -> quadtree");
}

TEST(OptionTable, EnumNamesAndTheirEnumeratorsRead) {
  EXPECT_EQ(parse_kernel_set("avx512bw"), KernelSet::avx512bw);
  EXPECT_EQ(parse_kernel_set("sse4_2"), KernelSet::sse4_2);
  EXPECT_EQ(parse_candidate_ranking("cross_score"), CandidateRanking::cross_score);
  EXPECT_EQ(parse_coordinate_map("pixel_centre"), CoordinateMap::pixel_centre);
  try {
    parse_mode("orb");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown mode 'orb' (expected aief, aief-paper, orbslam2, quadtree-entropy, "
                 "faithful or quality)");
  }
}

}  // namespace
}  // namespace aief

// The option table (core/options/option_table.hpp): every field of ExtractorOptions is a row, and
// every row reaches every front end (a CLI flag, an ORB-SLAM settings key, the output record; the
// Python keyword in python/tests/test_options.py), each given value taking effect. The number
// syntax, the enum names, and the one resolution rule (the mode first, the options given over it,
// conflicts refused).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <variant>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "aief/orbslam2_extractor.hpp"
#include "aief/version.hpp"
#include "core/options/option_names.hpp"
#include "core/options/acts_with.hpp"
#include "core/options/option_table.hpp"
#include "tests/field_count.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

namespace table = option_table;

using test::field_count;

std::vector<const table::OptionRow*> field_rows() {
  std::vector<const table::OptionRow*> out;
  for (const table::OptionRow& row : table::rows())
    if (row.is_field()) out.push_back(&row);
  return out;
}

// A value of the row other than its default, valid alone, as a front end writes it.
std::string other_value(const table::OptionRow& row) {
  const table::OptionValue value = row.field.get(ExtractorOptions{});
  switch (row.kind()) {
    case table::ValueKind::integer: {
      const long long v = std::get<long long>(value);
      return std::to_string(v + 1 <= row.high ? v + 1 : v - 1);
    }
    case table::ValueKind::number: {
      const double v = std::get<double>(value);
      if (v == 0) return table::text_of(row, row.high);  // 0 (off) scales to itself
      return table::text_of(row, v * 1.25 <= row.high ? v * 1.25 : v * 0.8);
    }
    case table::ValueKind::choice:
      for (std::string_view name : row.field.choices()->names)
        if (name != std::get<std::string_view>(value) && name != "off" && name != "avx2" &&
            name != "avx512" && name != "sse4.2" && name != "neon64")
          return std::string(
              name);  // off is a conflict with --threshold; a kernel set may be missing here
      break;
    case table::ValueKind::toggle:
      return table::text_of(row, !std::get<bool>(value));  // the drop-ins' too
  }
  return "";
}

TEST(OptionTable, EveryFieldOfExtractorOptionsIsARow) {
  EXPECT_EQ(field_count<ExtractorOptions>(), field_rows().size());
  ExtractorOptions changed;
  std::set<std::string_view> keys;
  for (const table::OptionRow* row : field_rows()) {
    EXPECT_TRUE(keys.insert(row->key).second) << row->key;
    // Each row's setter writes its own field: the record changes in that key alone.
    if (!row->has_front_ends()) continue;
    ExtractorOptions options;
    row->field.set(options, table::parse_value(*row, other_value(*row), row->key));
    const auto before = table::record_of(ExtractorOptions{}), after = table::record_of(options);
    int differing = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
      if (before[i].second != after[i].second) {
        ++differing;
        EXPECT_EQ(before[i].first, row->key);
      }
    EXPECT_EQ(differing, 1) << row->key;
  }
}

TEST(OptionTable, EveryRowHasEveryFrontEndOnce) {
  std::set<std::string_view> flags, keywords, yaml_keys;
  std::set<int> positions;
  for (const table::OptionRow& row : table::rows()) {
    SCOPED_TRACE(std::string(row.key));
    EXPECT_FALSE(row.help.empty());
    if (!row.has_front_ends()) {
      // Record-only rows are set through another row: distribution by the mode, auto_threshold by
      // --threshold auto, carried_threshold by --threshold carried.
      EXPECT_TRUE(row.key == "distribution" || row.key == "auto_threshold" ||
                  row.key == "carried_threshold");
      continue;
    }
    EXPECT_TRUE(row.cli_flag.starts_with("--") && flags.insert(row.cli_flag).second);
    EXPECT_TRUE(!row.python_keyword.empty() && keywords.insert(row.python_keyword).second);
    EXPECT_TRUE(row.yaml_key.starts_with("ORBextractor.") && yaml_keys.insert(row.yaml_key).second);
    if (row.python_position > 0) {
      EXPECT_TRUE(positions.insert(row.python_position).second);
    }
  }
  // One name per option (CHANGELOG.md): the flag and the keyword are the record key's; an earlier
  // spelling is no option's name and none other's earlier spelling.
  for (const table::OptionRow& row : table::rows()) {
    if (!row.has_front_ends()) continue;
    SCOPED_TRACE(std::string(row.key));
    if (row.key != "mode" && row.key != "auto_skips_uniform_blocks") {  // a preset; skip|count
      std::string flag = "--" + std::string(row.key);
      std::replace(flag.begin(), flag.end(), '_', '-');
      EXPECT_EQ(row.cli_flag, flag);
      EXPECT_EQ(row.python_keyword, row.key);
    }
    if (!row.old_cli_flag.empty())
      EXPECT_TRUE(row.old_cli_flag.starts_with("--") && flags.insert(row.old_cli_flag).second);
    if (!row.old_python_keyword.empty())
      EXPECT_TRUE(keywords.insert(row.old_python_keyword).second);
    if (!row.old_yaml_key.empty())
      EXPECT_TRUE(row.old_yaml_key.starts_with("ORBextractor.") &&
                  yaml_keys.insert(row.old_yaml_key).second);
  }
  EXPECT_EQ(positions.size(), 7u);
}

using CliResult = aief::test::CommandRun;  // status, and stdout + stderr

CliResult run_cli(const std::string& arguments) {
  return aief::test::run_shell(std::string(AIEF_CLI_PATH) + " " + arguments);
}

// The JSON text the record holds for `text` given to `row`.
std::string record_json(const table::OptionRow& row, const std::string& text) {
  ExtractorOptions options;
  row.field.set(options, table::parse_value(row, text, row.key));
  for (const auto& [key, value] : table::record_of(options))
    if (key == row.key) {
      if (const auto* name = std::get_if<std::string_view>(&value))
        return "\"" + std::string(*name) + "\"";
      if (const auto* flag = std::get_if<bool>(&value)) return *flag ? "true" : "false";
      if (const auto* integer = std::get_if<long long>(&value)) return std::to_string(*integer);
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.17g",
                    std::get<double>(value));  // io/json_writer.cpp's format
      return buffer;
    }
  return "";
}

// What a row needs beside it to act (its acts_with conditions the defaults do not meet), as
// (key, text) of the rows that set them: the quadtree by a mode that keeps the mask, the
// automatic and the carried F by the threshold's word.
std::vector<std::pair<std::string_view, std::string>> companions(const table::OptionRow& row) {
  std::vector<std::pair<std::string_view, std::string>> out;
  ExtractorOptions options;
  row.field.set(options, table::parse_value(row, other_value(row), row.key));
  for (table::UnmetCondition unmet = table::unmet_condition(row, options); unmet.row;
       unmet = table::unmet_condition(row, options)) {
    const std::string_view key = unmet.row->key;
    if (key == "distribution")
      out.emplace_back("mode", "quadtree-entropy");
    else if (key == "auto_threshold")
      out.emplace_back("entropy_threshold", "auto");
    else if (key == "carried_threshold")
      out.emplace_back("entropy_threshold", "carried");
    else
      out.emplace_back(key, unmet.needed);
    unmet.row->field.set(options, table::parse_value(*unmet.row, unmet.needed, key));
  }
  return out;
}

TEST(OptionTable, EveryCliFlagReachesTheOutputRecord) {
  const test::TempFolder folder("aief_option_table");
  const std::string image = test::sample_path("boat", "img1.png");
  for (const table::OptionRow& row : table::rows()) {
    if (!row.is_field() || !row.has_front_ends()) continue;
    const std::string value = other_value(row), output = folder.file("f.json");
    std::string beside;
    for (const auto& [key, text] : companions(row))
      beside += " " + std::string(table::row(key).cli_flag) + " " + text;
    for (std::string_view flag : {row.cli_flag, row.old_cli_flag}) {  // the earlier one too
      if (flag.empty()) continue;
      const CliResult r = run_cli("extract " + image + " " + std::string(flag) + " " + value +
                                  beside + " -o " + output);
      ASSERT_EQ(r.status, 0) << flag << " " << value << "\n" << r.output;
      std::ifstream in(output);
      const std::string json((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      const std::string expected = "\"" + std::string(row.key) + "\":" + record_json(row, value);
      EXPECT_NE(json.find(expected), std::string::npos)
          << flag << " " << value << ": no " << expected;
    }
  }
  // --help lists every flag.
  const CliResult help = run_cli("extract --help");
  for (const table::OptionRow& row : table::rows())
    if (row.has_front_ends()) {
      EXPECT_NE(help.output.find(std::string(row.cli_flag) + " "), std::string::npos)
          << row.cli_flag;
    }
}

TEST(OptionTable, EverySettingsKeyReachesTheOptions) {
  for (const table::OptionRow& row : table::rows()) {
    if (!row.is_field() || !row.has_front_ends()) continue;
    const std::string value = other_value(row);
    const bool is_text =
        row.kind() == table::ValueKind::choice || row.kind() == table::ValueKind::toggle;
    // In AIEF mode, where every key applies (the drop-ins' own mode, orbslam2, has no mask),
    // with what the key needs to act.
    std::string aief_mode = "%YAML:1.0\n";
    std::string mode = "aief";
    for (const auto& [key, text] : companions(row)) {
      if (key == "mode") mode = text;
      else aief_mode += std::string(table::row(key).yaml_key) + ": \"" + text + "\"\n";
    }
    aief_mode += "ORBextractor.mode: \"" + mode + "\"\n";
    for (std::string_view key : {row.yaml_key, row.old_yaml_key}) {  // the earlier key is read too
      if (key.empty()) continue;
      const std::string yaml =
          aief_mode + std::string(key) + ": " + (is_text ? "\"" + value + "\"" : value) + "\n";
      const cv::FileStorage settings(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
      const ExtractorOptions options = ORBextractor::options_from_settings(settings);
      // The drop-ins' defaults (ORB-SLAM's keypoint convention) with the one key changed.
      ExtractorOptions expected = ORBextractor::options_from_settings(
          cv::FileStorage(aief_mode, cv::FileStorage::READ | cv::FileStorage::MEMORY));
      row.field.set(expected, table::parse_value(row, value, row.key));
      expected.scale_factor =
          static_cast<float>(expected.scale_factor);  // read into a float, as Tracking.cc
      EXPECT_EQ(table::record_of(options), table::record_of(expected)) << key << ": " << value;
    }
  }
}

// Without a mode the drop-ins run ORB-SLAM's choices (orbslam2: no mask, quadtree; docs/slam.md
// "Which choice costs what"); an AIEF option then is refused, saying which mode it needs.
TEST(OptionTable, DropInsDefaultToOrbSlam2ModeAndSayWhatAnAiefKeyNeeds) {
  const auto settings = [](const std::string& body) {
    return cv::FileStorage("%YAML:1.0\n" + body, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  };
  const ExtractorOptions plain = ORBextractor::options_from_settings(
      settings("Camera.bf: 47.9\nORBextractor.nFeatures: 800\n"));  // a stereo rig's settings
  EXPECT_EQ(table::record_of(plain), table::record_of([] {
              ExtractorOptions o = options_for_mode(Mode::orbslam2);
              o.n_features = 800;
              o.scale_factor = static_cast<float>(o.scale_factor);  // as Tracking.cc reads it
              return o;
            }()));
  EXPECT_EQ(
      ORBextractor::options_from_settings(settings("ORBextractor.mode: \"aief\"\n")).distribution,
      Distribution::proportional);
  try {
    ORBextractor::options_from_settings(settings("ORBextractor.entropyThreshold: 4.5\n"));
    ADD_FAILURE() << "an entropy threshold without a mode was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("ORBextractor.entropyThreshold"), std::string::npos) << message;
    EXPECT_NE(message.find("ORBextractor.mode: \"aief\""), std::string::npos) << message;
  }
  // A bad value is only that: no word about the mode.
  try {
    ORBextractor::options_from_settings(settings("ORBextractor.nLevels: 7.5\n"));
    ADD_FAILURE() << "nLevels 7.5 accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("ORBextractor.mode"), std::string::npos) << e.what();
  }
  // A named mode's own refusal carries no hint about the default.
  try {
    ORBextractor::options_from_settings(
        settings("ORBextractor.mode: \"orbslam2\"\nORBextractor.entropyThreshold: 4.5\n"));
    ADD_FAILURE() << "an entropy threshold in orbslam2 mode was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("when the settings name none"), std::string::npos)
        << e.what();
  }
}

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
  EXPECT_EQ(table::text_of(table::OptionDifference{"ratio", "0.69999999999999996",
                                                   "0.80000000000000004"}),
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

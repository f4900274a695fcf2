// The option table (core/options/option_table.hpp): every field of ExtractorOptions is a row, and
// every row reaches every front end (a CLI flag, an ORB-SLAM settings key, the output record; the
// Python keyword in python/tests/test_options.py), each given value taking effect; the drop-ins'
// default mode. The number syntax, the enum names and the one resolution rule:
// tests/test_option_resolution.cpp.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <variant>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "aief/orbslam2_extractor.hpp"
#include "core/options/acts_with.hpp"
#include "core/options/option_table.hpp"
#include "tests/cli_run.hpp"
#include "tests/field_count.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

namespace table = option_table;

using test::CliResult;
using test::field_count;
using test::run_cli;

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
      // --entropy-threshold auto, carried_threshold by --entropy-threshold carried.
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
    if (!row.old_cli_flag.empty()) {
      EXPECT_TRUE(row.old_cli_flag.starts_with("--") && flags.insert(row.old_cli_flag).second);
    }
    if (!row.old_python_keyword.empty()) {
      EXPECT_TRUE(keywords.insert(row.old_python_keyword).second);
    }
    if (!row.old_yaml_key.empty()) {
      EXPECT_TRUE(row.old_yaml_key.starts_with("ORBextractor.") &&
                  yaml_keys.insert(row.old_yaml_key).second);
    }
  }
  EXPECT_EQ(positions.size(), 7u);
}

// The JSON text the record holds for `text` given to `row`.
std::string record_json(const table::OptionRow& row, const std::string& text) {
  ExtractorOptions options;
  row.field.set(options, table::parse_value(row, text, row.key));
  for (const auto& [key, value] : table::record_of(options))
    if (key == row.key) {
      if (const auto* name = std::get_if<std::string_view>(&value))
        return std::string("\"").append(*name).append("\"");  // appended: GCC 12's -Wrestrict
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
  const std::string frames = folder.file("frames");
  std::filesystem::create_directories(frames);
  std::filesystem::copy_file(image, frames + "/img1.png");
  for (const table::OptionRow& row : table::rows()) {
    if (!row.is_field() || !row.has_front_ends()) continue;
    const std::string value = other_value(row), output = folder.file("f.json");
    std::string beside;
    for (const auto& [key, text] : companions(row))
      beside.append(" ").append(table::row(key).cli_flag).append(" ").append(text);
    // The carried F acts on a video only: its rows are extracted as a one-frame --batch.
    const bool video = beside.find(" carried") != std::string::npos;
    for (std::string_view flag : {row.cli_flag, row.old_cli_flag}) {  // the earlier one too
      if (flag.empty()) continue;
      std::string flags(" ");  // appended, not summed: GCC 12 warns falsely (-Wrestrict) on the sum
      flags.append(flag).append(" ").append(value).append(beside);
      const CliResult r =
          video ? run_cli("extract --batch " + frames + flags + " -o " + folder.file("video"))
                : run_cli("extract " + image + flags + " -o " + output);
      ASSERT_EQ(r.status, 0) << flag << " " << value << "\n" << r.output;
      std::ifstream in(video ? folder.file("video/img1.png.json") : output);
      const std::string json((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      const std::string expected =
          std::string("\"").append(row.key).append("\":").append(record_json(row, value));
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
      if (key == "mode")
        mode = text;
      else
        aief_mode += std::string(table::row(key).yaml_key) + ": \"" + text + "\"\n";
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

}  // namespace
}  // namespace aief

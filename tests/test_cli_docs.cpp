// docs/command_line.md's synopsis has every flag of every command, as the built tool's `--help`
// lists them (the commands from `aief --help`, their flags from `aief <command> --help`), and no
// flag the command does not have. A flag added to the tool fails here until the synopsis has it.
#include <cctype>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/feature_formats.hpp"
#include "tests/test_support.hpp"

namespace {

const std::regex kLongFlag(R"((^|[^A-Za-z0-9_-])(--[a-z][a-z0-9-]*)(?![A-Za-z0-9_]))");

std::set<std::string> long_flags_in(const std::string& text) {
  std::set<std::string> flags;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kLongFlag);
       it != std::sregex_iterator(); ++it)
    flags.insert((*it)[2].str());
  return flags;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string help_of(const std::vector<std::string>& arguments) {
  const aief::test::CommandRun run = aief::test::run_command(AIEF_CLI_PATH, arguments);
  EXPECT_EQ(run.status, 0) << run.output;
  return run.output;
}

// The flags a help text offers: those in its usage lines and in its option rows (a line indented
// by two spaces that starts with a flag: "  -o, --output FILE  ...", "  --pool P|inf, --ranking
// R,"). Each long flag maps to its one-letter form, if it has one ("-o"), or "".
std::map<std::string, std::string> flags_of_help(const std::string& help) {
  static const std::regex usage_line(R"(^(usage: |\s+)aief\b.*)");
  static const std::regex option_row(R"(^  (-[A-Za-z], )?--[a-z].*)");
  static const std::regex short_and_long(R"(^  (-[A-Za-z]), (--[a-z][a-z0-9-]*))");
  std::map<std::string, std::string> flags;
  for (const std::string& line : lines_of(help)) {
    if (!std::regex_match(line, usage_line) && !std::regex_match(line, option_row)) continue;
    for (const std::string& flag : long_flags_in(line)) flags.emplace(flag, "");
    std::smatch pair;
    if (std::regex_search(line, pair, short_and_long)) flags[pair[2].str()] = pair[1].str();
  }
  return flags;
}

// The commands `aief --help` lists: the rows of its "commands:" section.
std::vector<std::string> commands_of_help(const std::string& help) {
  static const std::regex command_row(R"(^  ([a-z]+)\s{2,}\S.*)");
  std::vector<std::string> commands;
  bool in_section = false;
  for (const std::string& line : lines_of(help)) {
    if (line == "commands:") {
      in_section = true;
      continue;
    }
    if (in_section && line.empty()) break;
    std::smatch row;
    if (in_section && std::regex_match(line, row, command_row)) commands.push_back(row[1].str());
  }
  return commands;
}

// The synopsis, the first ```sh block of docs/command_line.md, by command: the lines that start
// `build/aief <command>` and their indented continuations ("" gathers `build/aief --flag` and
// `build/aief <command> --help`); "[extractor options]" stands for the "extractor options:" lines.
std::map<std::string, std::string> synopsis_by_command(const std::string& doc) {
  const std::size_t begin = doc.find("```sh\n");
  const std::size_t end = doc.find("\n```", begin + 1);
  EXPECT_NE(begin, std::string::npos) << "no ```sh block in docs/command_line.md";
  std::map<std::string, std::string> synopsis;
  if (begin == std::string::npos || end == std::string::npos) return synopsis;
  std::string current;
  bool in_entry = false;
  for (const std::string& line : lines_of(doc.substr(begin + 6, end - begin - 6))) {
    static const std::regex entry(R"(^build/aief (\S+).*)");
    std::smatch start;
    if (std::regex_match(line, start, entry)) {
      const std::string word = start[1].str();
      current = word[0] == '-' || word[0] == '<' ? "" : word;
      in_entry = true;
    } else if (line == "extractor options:") {
      current = "[extractor options]";
      in_entry = true;
    } else if (line.empty() || !std::isspace(static_cast<unsigned char>(line[0]))) {
      in_entry = false;
    }
    if (in_entry) synopsis[current] += line + "\n";
  }
  // "[extractor options but --mode, --threads]": the block without those flags' [items].
  static const std::regex but(R"(\[extractor options but ([^\]]*)\])");
  for (auto& [command, text] : synopsis) {
    if (command == "[extractor options]") continue;
    if (text.find("[extractor options]") != std::string::npos)
      text += synopsis["[extractor options]"];
    std::smatch excepted;
    if (!std::regex_search(text, excepted, but)) continue;
    std::string block = synopsis["[extractor options]"];
    for (const std::string& flag : long_flags_in(excepted[1].str()))
      block = std::regex_replace(block, std::regex("\\[" + flag + "( [^\\]]*)?\\]"), "");
    text = excepted.prefix().str() + excepted.suffix().str() + block;
  }
  return synopsis;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool mentions(const std::string& text, const std::string& flag) {
  if (flag.rfind("--", 0) == 0) return long_flags_in(text).count(flag) > 0;
  return std::regex_search(text, std::regex("(^|[^A-Za-z0-9_-])" + flag + "([^A-Za-z0-9_-]|$)"));
}

TEST(CommandLineDoc, SynopsisHasEveryFlagOfEveryCommandAndNoOther) {
  const std::map<std::string, std::string> synopsis =
      synopsis_by_command(read_text(AIEF_DOCS_DIR "/command_line.md"));
  const std::string top_help = help_of({"--help"});
  std::vector<std::string> commands = commands_of_help(top_help);
  ASSERT_GE(commands.size(), 8u) << top_help;  // extract, match, adapt, eval, bench, validate, ...
  commands.insert(commands.begin(), "");       // the tool's own flags: --help, --version, ...
  for (const std::string& command : commands) {
    SCOPED_TRACE("aief " + command);
    const auto documented = synopsis.find(command);
    ASSERT_NE(documented, synopsis.end()) << "no `build/aief " << command << "` line";
    const std::string help = command.empty() ? top_help : help_of({command, "--help"});
    const std::map<std::string, std::string> flags = flags_of_help(help);
    for (const auto& [flag, short_form] : flags)
      EXPECT_TRUE(mentions(documented->second, flag) ||
                  (!short_form.empty() && mentions(documented->second, short_form)))
          << flag << " is not in the synopsis of docs/command_line.md:\n"
          << documented->second;
    for (const std::string& flag : long_flags_in(documented->second))
      EXPECT_TRUE(flags.count(flag)) << flag << " is in the synopsis but not in --help";
  }
}

// Every row of the format registry (io/feature_formats.cpp) is in aief extract --help, which is
// made from the rows, and in the synopsis's --format choices: a new format's only hand-written
// mention outside docs/feature_files.md.
TEST(CommandLineDoc, EveryFeaturesFormatIsInExtractHelpAndTheSynopsis) {
  const std::string help = help_of({"extract", "--help"});
  const std::string synopsis =
      synopsis_by_command(read_text(AIEF_DOCS_DIR "/command_line.md"))["extract"];
  std::string choices;  // every "--format a|b|c" of the synopsis
  static const std::regex format_choice(R"(--format ([a-z0-9|]+))");
  for (auto it = std::sregex_iterator(synopsis.begin(), synopsis.end(), format_choice);
       it != std::sregex_iterator(); ++it)
    choices += "|" + (*it)[1].str() + "|";
  for (const aief::io::FeatureFormat& format : aief::io::feature_formats()) {
    SCOPED_TRACE(format.name);
    EXPECT_TRUE(mentions(help, std::string(format.name))) << help;
    EXPECT_NE(help.find(format.extensions.front()), std::string::npos) << help;
    EXPECT_NE(choices.find(std::string("|") + format.name + "|"), std::string::npos)
        << "--format " << format.name << " is not in the synopsis of docs/command_line.md";
  }
}

}  // namespace

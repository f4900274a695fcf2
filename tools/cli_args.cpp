#include "tools/cli_args.hpp"

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "aief/error.hpp"
#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"
#include "parallel/scheduler.hpp"

namespace aief::cli {

Args::Args(const std::vector<std::string>& tokens, const std::vector<FlagSpec>& spec) {
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& token = tokens[i];
    if (token.size() < 2 || token[0] != '-' ||
        (std::isdigit(static_cast<unsigned char>(token[1])) != 0)) {
      positionals_.push_back(token);
      continue;
    }
    std::string name = token, inline_value;
    bool has_inline = false;
    if (const std::size_t eq = token.find('=');
        eq != std::string::npos && token.rfind("--", 0) == 0) {
      name = token.substr(0, eq);
      inline_value = token.substr(eq + 1);
      has_inline = true;
    }
    const FlagSpec* match = nullptr;
    for (const FlagSpec& flag : spec)
      if (flag.name == name || (!flag.alias.empty() && flag.alias == name)) match = &flag;
    if (!match) throw UsageError("unknown option " + name);
    refuse_a_second_time(match->name, name);
    spellings_.push_back(name);
    if (!match->takes_value) {
      if (has_inline) throw UsageError(name + " takes no value");
      values_.emplace_back(match->name, "");
      continue;
    }
    if (has_inline) {
      values_.emplace_back(match->name, inline_value);
    } else {
      if (i + 1 >= tokens.size()) throw UsageError(name + " expects a value");
      values_.emplace_back(match->name, tokens[++i]);
    }
  }
}

void Args::refuse_a_second_time(const std::string& flag, const std::string& spelling) const {
  for (std::size_t i = 0; i < values_.size(); ++i) {
    if (values_[i].first != flag) continue;
    const std::string& before = spellings_[i];
    if (before == spelling) throw UsageError(spelling + " is given twice: give it once");
    throw UsageError(before + " and " + spelling +
                     " are two spellings of one option, both given: give it once");
  }
}

bool Args::has(const std::string& name) const {
  for (const auto& [flag, value] : values_)
    if (flag == name) return true;
  return false;
}

std::vector<std::string> Args::flags_given() const {
  std::vector<std::string> flags;
  for (const auto& [flag, value] : values_) flags.push_back(flag);
  return flags;
}

std::string Args::spelled(const std::string& name) const {
  std::string spelling = name;
  for (std::size_t i = 0; i < values_.size(); ++i)
    if (values_[i].first == name) spelling = spellings_[i];
  return spelling;
}

std::optional<std::string> Args::get(const std::string& name) const {
  for (const auto& [flag, value] : values_)
    if (flag == name) return value;  // given once at most (refuse_a_second_time)
  return std::nullopt;
}

int Args::get_int(const std::string& name, int fallback, int min, int max) const {
  const std::optional<std::string> text = get(name);
  if (!text) return fallback;
  long long value = 0;
  if (!option_table::parse_integer(*text, value) || value < min || value > max)
    throw UsageError(name + " expects an integer in [" + std::to_string(min) + ", " +
                     std::to_string(max) + "], got '" + *text + "'");
  return static_cast<int>(value);
}

std::optional<Args> command_args(const std::vector<std::string>& tokens, std::vector<FlagSpec> spec,
                                 void (*print_help)()) {
  spec.push_back({"--help", "-h", false});
  Args args(tokens, spec);
  if (!args.has("--help")) return args;
  print_help();
  return std::nullopt;
}

namespace {

// --help's lines of `Options`' flags: the flag and its placeholder, then the help (the names of a
// choice, the default) wrapped at 100 columns.
// `except`: record keys of rows left out.
template <class Options>
bool is_among(const option_table::Row<Options>& row, const std::vector<std::string_view>& keys) {
  for (std::string_view key : keys)
    if (row.key == key) return true;
  return false;
}

constexpr std::size_t kHelpColumn = 24, kHelpWidth = 100;

// One flag's --help line: `label` ("  --flag VALUE"), then `text` from column 24 wrapped at 100
// columns (on the next line when the label reaches column 24); a '\n' in `text` starts a line,
// and a line that starts with two spaces (a command to copy) is written whole.
std::string help_line(const std::string& label, const std::string& text) {
  std::string line = label;
  line += line.size() + 1 < kHelpColumn ? std::string(kHelpColumn - line.size(), ' ')
                                        : "\n" + std::string(kHelpColumn, ' ');
  std::istringstream paragraphs(text);
  bool first = true;
  for (std::string paragraph; std::getline(paragraphs, paragraph); first = false) {
    if (!first) line += "\n" + std::string(kHelpColumn, ' ');
    if (paragraph.rfind("  ", 0) == 0) {  // a command to copy whole: never broken
      line += paragraph.substr(2);
      continue;
    }
    std::istringstream words(paragraph);
    std::size_t used = kHelpColumn;
    for (std::string word; words >> word;) {
      if (used + 1 + word.size() > kHelpWidth && used > kHelpColumn) {
        line += "\n" + std::string(kHelpColumn, ' ');
        used = kHelpColumn;
      } else if (used > kHelpColumn && line.back() != ' ') {
        line += ' ';
        ++used;
      }
      line += word;
      used += word.size();
    }
  }
  return line + "\n";
}

template <class Options>
std::string help_of_rows(const std::vector<std::string_view>& except = {}) {
  constexpr std::size_t kWidth = kHelpWidth;
  std::ostringstream out;
  for (const option_table::Row<Options>& row : option_table::rows_of<Options>()) {
    if (row.cli_flag.empty() || is_among(row, except)) continue;
    std::string text = std::string(row.help) + " (";
    if (row.kind() == option_table::ValueKind::choice)
      text += option_table::expected_values(row) + "; ";
    text += "default " + option_table::defaults_text(row) + ")";
    out << help_line("  " + std::string(row.cli_flag) + " " + std::string(row.cli_value), text);
  }
  // The earlier spellings, on lines of their own (not option rows: docs/command_line.md lists
  // them in its changelog note, not in its synopsis).
  std::vector<std::string> old;
  for (const option_table::Row<Options>& row : option_table::rows_of<Options>())
    if (!row.cli_flag.empty() && !row.old_cli_flag.empty() && !is_among(row, except))
      old.push_back(std::string(row.old_cli_flag) + " (" + std::string(row.cli_flag) + ")");
  if (!old.empty()) {
    std::string line = "  earlier spellings, still accepted (CHANGELOG.md):";
    for (std::size_t i = 0; i < old.size(); ++i) {
      const std::string item = old[i] + (i + 1 < old.size() ? "," : "");
      if (line.size() + 1 + item.size() > kWidth) {
        out << line << "\n";
        line = "   ";
      }
      line += " " + item;
    }
    out << line << "\n";
  }
  return out.str();
}

template <class Options>
std::vector<option_table::Given<Options>> given_flags(const Args& args) {
  std::vector<option_table::Given<Options>> given;
  for (const option_table::Row<Options>& row : option_table::rows_of<Options>())
    if (!row.cli_flag.empty())
      if (const auto text = args.get(std::string(row.cli_flag)))
        given.push_back({&row, *text, args.spelled(std::string(row.cli_flag))});
  return given;
}

template <class Options>
std::vector<FlagSpec> flags_except(const std::vector<std::string_view>& except) {
  std::vector<FlagSpec> flags;
  for (const option_table::Row<Options>& row : option_table::rows_of<Options>())
    if (!row.cli_flag.empty() && !is_among(row, except))
      flags.push_back({std::string(row.cli_flag), std::string(row.old_cli_flag), true});
  return flags;
}

}  // namespace

std::string help_of(const std::vector<FlagSpec>& flags) {
  std::string out;
  for (const FlagSpec& flag : flags) {
    if (flag.help.empty()) continue;
    const bool short_alias = flag.alias.size() == 2 && flag.alias[0] == '-';
    std::string label = "  " + (short_alias ? flag.alias + ", " : "") + flag.name;
    if (flag.takes_value) label += " " + flag.value;
    out += help_line(label, flag.help);
  }
  return out;
}

template <class Options>
std::vector<FlagSpec> flags_of() {
  return flags_except<Options>({});
}

template <class Options>
Options options_from_flags(const Args& args, Options base) {
  try {
    return option_table::resolve_options(given_flags<Options>(args), option_table::FrontEnd::cli,
                                         base);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

template <class Options>
std::string flags_help() {
  return help_of_rows<Options>();
}

template std::vector<FlagSpec> flags_of<MatchOptions>();
template std::vector<FlagSpec> flags_of<SweepOptions>();
template MatchOptions options_from_flags(const Args&, MatchOptions);
template SweepOptions options_from_flags(const Args&, SweepOptions);
template std::string flags_help<MatchOptions>();
template std::string flags_help<SweepOptions>();

std::vector<FlagSpec> extractor_flags() { return flags_of<ExtractorOptions>(); }

std::vector<FlagSpec> extractor_flags_except(
    const std::vector<std::string_view>& set_by_the_command) {
  return flags_except<ExtractorOptions>(set_by_the_command);
}

void refuse_carried_threshold(const Args& args, const ExtractorOptions& options,
                              const std::string& command) {
  if (!options.carried_threshold) return;
  throw UsageError(args.spelled("--entropy-threshold") +
                   " carried takes F from the frames of a video before each one, and " + command +
                   " has no frame before its images, so F would stay at its start: extract a "
                   "video with extract --batch, or give F");
}

void require_entropy_to_sweep(const Args& args, const ExtractorOptions& options,
                              const std::string& command) {
  if (options.entropy != EntropyMeasure::off) return;
  const auto mode = args.get("--mode");
  const std::string how = args.has("--entropy") ? args.spelled("--entropy") + " off"
                          : mode                ? args.spelled("--mode") + " " + *mode
                                                : std::string("the options given");
  std::string with_entropy;  // the modes that measure it, from their own options
  for (const auto& mode : option_names::Table<Mode>::names)
    if (options_for_mode(mode.value).entropy != EntropyMeasure::off)
      with_entropy += (with_entropy.empty() ? "" : ", ") + std::string(mode.name);
  throw UsageError(command + " sweeps the entropy threshold, and " + how +
                   " measures no entropy: give a mode that does (" + with_entropy + ")");
}

ExtractorOptions extractor_options(const Args& args, option_table::Use use) {
  ExtractorOptions options;
  try {
    options = option_table::resolve_options(given_flags<ExtractorOptions>(args), use);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (const std::string note = parallel::cap_threads(options.threads, "--threads"); !note.empty())
    std::cerr << "aief: note: " << note << "\n";
  return options;
}

std::string extractor_flags_help() {
  return help_of_rows<ExtractorOptions>() +
         "  (a mode sets the options it names; the options given apply after it)\n";
}

std::string extractor_flags_help_except(const std::vector<std::string_view>& set_by_the_command) {
  return help_of_rows<ExtractorOptions>(set_by_the_command);
}

std::vector<std::string> flags_outside(const Args& args, const std::vector<FlagSpec>& applying) {
  std::vector<std::string> outside;
  for (const std::string& flag : args.flags_given()) {
    bool applies = false;
    for (const FlagSpec& spec : applying) applies = applies || spec.name == flag;
    bool listed = false;
    for (const std::string& seen : outside) listed = listed || seen == flag;
    if (!applies && !listed) outside.push_back(flag);
  }
  return outside;
}

}  // namespace aief::cli

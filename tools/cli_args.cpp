#include "tools/cli_args.hpp"

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include <tbb/info.h>

#include "aief/error.hpp"
#include "core/option_table.hpp"

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
    if (!match->takes_value) {
      if (has_inline) throw UsageError(match->name + " takes no value");
      values_.emplace_back(match->name, "");
      continue;
    }
    if (has_inline) {
      values_.emplace_back(match->name, inline_value);
    } else {
      if (i + 1 >= tokens.size()) throw UsageError(match->name + " expects a value");
      values_.emplace_back(match->name, tokens[++i]);
    }
  }
}

bool Args::has(const std::string& name) const {
  for (const auto& [flag, value] : values_)
    if (flag == name) return true;
  return false;
}

std::optional<std::string> Args::get(const std::string& name) const {
  std::optional<std::string> result;
  for (const auto& [flag, value] : values_)
    if (flag == name) result = value;  // the last one wins
  return result;
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

double Args::get_double(const std::string& name, double fallback, double min, double max,
                        bool min_is_exclusive) const {
  const std::optional<std::string> text = get(name);
  if (!text) return fallback;
  double value = 0;
  const bool parsed = option_table::parse_decimal(*text, value);
  const bool below = min_is_exclusive ? value <= min : value < min;
  if (!parsed || below || value > max) {
    std::ostringstream message;
    message << name << " expects a number in " << (min_is_exclusive ? "(" : "[") << min << ", "
            << max << "], got '" << *text << "'";
    throw UsageError(message.str());
  }
  return value;
}

std::vector<FlagSpec> extractor_flags() {
  std::vector<FlagSpec> flags;
  for (const option_table::OptionRow& row : option_table::rows())
    if (row.has_front_ends()) flags.push_back({std::string(row.cli_flag), "", true});
  return flags;
}

ExtractorOptions extractor_options(const Args& args) {
  std::vector<option_table::GivenOption> given;
  for (const option_table::OptionRow& row : option_table::rows())
    if (row.has_front_ends())
      if (const auto text = args.get(std::string(row.cli_flag)))
        given.push_back({&row, *text, std::string(row.cli_flag)});
  ExtractorOptions options;
  try {
    options = option_table::resolve_options(given);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  // More threads than the machine runs gains nothing (output never depends on the count) and
  // makes TBB print its own warning: use what there is, and say so.
  if (const int available = tbb::info::default_concurrency(); options.threads > available) {
    std::cerr << "aief: note: --threads " << options.threads << " is more than the " << available
              << " hardware threads this process may use; using " << available << "\n";
    options.threads = available;
  }
  return options;
}

std::string extractor_flags_help() {
  // Two columns: the flag and its placeholder, then the help wrapped at 100 columns.
  constexpr std::size_t kColumn = 24, kWidth = 100;
  std::ostringstream out;
  for (const option_table::OptionRow& row : option_table::rows()) {
    if (!row.has_front_ends()) continue;
    std::string line = "  " + std::string(row.cli_flag) + " " + std::string(row.cli_value);
    line += line.size() + 1 < kColumn ? std::string(kColumn - line.size(), ' ')
                                      : "\n" + std::string(kColumn, ' ');
    std::string text = std::string(row.help) + " (";
    if (row.kind() == option_table::ValueKind::choice)
      text += option_table::expected_values(row) + "; ";
    text += "default " + option_table::defaults_text(row) + ")";
    std::istringstream words(text);
    std::size_t used = kColumn;
    for (std::string word; words >> word;) {
      if (used + 1 + word.size() > kWidth && used > kColumn) {
        line += "\n" + std::string(kColumn, ' ');
        used = kColumn;
      } else if (used > kColumn && line.back() != ' ') {
        line += ' ';
        ++used;
      }
      line += word;
      used += word.size();
    }
    out << line << "\n";
  }
  out << "  (a mode sets the options it names; the options given apply after it)\n";
  return out.str();
}

}  // namespace aief::cli

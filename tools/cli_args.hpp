#pragma once
// A tiny command-line parser for the aief subcommands: flags with or without a value,
// positionals, numbers checked with messages that name the flag and the value.
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "aief/match.hpp"
#include "aief/options.hpp"
#include "core/options/option_table.hpp"

namespace aief::cli {

// A mistake in the command line: exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A flag of a command, and its line in the command's --help: the one place a command's own flag
// is written (the option rows' flags come from their rows: flags_of, extractor_flags).
struct FlagSpec {
  std::string name;   // "--output"
  std::string alias;  // "-o", an earlier spelling ("--threshold"), or empty
  bool takes_value = true;
  std::string value = {};  // --help's placeholder: "FILE"
  // --help's text: '\n' starts a line, a line starting with two spaces is never broken; empty:
  // --help lists the flag elsewhere.
  std::string help = {};
};

// --help's lines of the flags with help, in order: "  -o, --output FILE     text", the text
// wrapped at 100 columns from column 24, as the option rows' lines are.
std::string help_of(const std::vector<FlagSpec>& flags);

class Args {
 public:
  // Throws UsageError for an unknown flag, a flag missing its value, or a flag given twice (by
  // one spelling or by its name and its alias), naming both: the last is not silently taken.
  Args(const std::vector<std::string>& tokens, const std::vector<FlagSpec>& spec);

  bool has(const std::string& name) const;
  std::optional<std::string> get(const std::string& name) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  // The flags given, by their names (aliases as their flag), in command-line order.
  std::vector<std::string> flags_given() const;
  // How the command line spelled the flag `name` (its name or its alias): what messages call it.
  // `name` itself when not given.
  std::string spelled(const std::string& name) const;

  int get_int(const std::string& name, int fallback, int min, int max) const;

 private:
  // Throws UsageError when `flag` (a spec's name) was given before, naming both spellings.
  void refuse_a_second_time(const std::string& flag, const std::string& spelling) const;

  std::vector<std::pair<std::string, std::string>> values_;  // flag name, value ("" for switches)
  std::vector<std::string> spellings_;                       // as given, beside values_
  std::vector<std::string> positionals_;
};

// A command's arguments read by `spec` with -h/--help added. Asked for help, prints it
// (`print_help`) and returns nothing: the command ends there, successfully.
std::optional<Args> command_args(const std::vector<std::string>& tokens, std::vector<FlagSpec> spec,
                                 void (*print_help)());

// The flags of an options struct's rows (core/options/option_table.hpp: MatchOptions,
// SweepOptions), the options they set over `base` (throws UsageError), and their --help lines with
// the defaults.
template <class Options>
std::vector<FlagSpec> flags_of();
template <class Options>
Options options_from_flags(const Args& args, Options base = {});
template <class Options>
std::string flags_help();

// The flags given that are not among `applying`, each once: what a command refuses.
std::vector<std::string> flags_outside(const Args& args, const std::vector<FlagSpec>& applying);

// Flags every command that extracts shares, and the options they set (defaults from
// ExtractorOptions, never repeated here).
std::vector<FlagSpec> extractor_flags();
ExtractorOptions extractor_options(const Args& args,
                                   option_table::Use use = option_table::Use::extraction);
std::string extractor_flags_help();
// The carried F (`--entropy-threshold carried`) takes F from the frames before: a command on one
// image or one pair (`command` names it) has none, so it is refused rather than left at its start.
void refuse_carried_threshold(const Args& args, const ExtractorOptions& options,
                              const std::string& command);
// What sweeps entropy thresholds (`adapt`, `match --adaptive`, `bench --pair`: `command` names
// it) needs an entropy measure: throws UsageError naming how the command line turned it off.
void require_entropy_to_sweep(const Args& args, const ExtractorOptions& options,
                              const std::string& command);
// The same but the rows of `set_by_the_command` (record keys): a command that sets those options
// itself (aief eval's rows: the mode, F, one thread) neither offers nor lists their flags.
std::vector<FlagSpec> extractor_flags_except(
    const std::vector<std::string_view>& set_by_the_command);
std::string extractor_flags_help_except(const std::vector<std::string_view>& set_by_the_command);

}  // namespace aief::cli

#pragma once
// A tiny command-line parser for the aief subcommands: flags with or without a value,
// positionals, numbers checked with messages that name the flag and the value.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "aief/match.hpp"
#include "aief/options.hpp"

namespace aief::cli {

// A mistake in the command line: exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct FlagSpec {
  std::string name;   // "--features"
  std::string alias;  // "-o", or empty
  bool takes_value = true;
};

class Args {
 public:
  // Throws UsageError for an unknown flag or a flag missing its value.
  Args(const std::vector<std::string>& tokens, const std::vector<FlagSpec>& spec);

  bool has(const std::string& name) const;
  std::optional<std::string> get(const std::string& name) const;
  const std::vector<std::string>& positionals() const { return positionals_; }

  int get_int(const std::string& name, int fallback, int min, int max) const;
  // The value must lie in [min, max], or in (min, max] when min_is_exclusive.
  double get_double(const std::string& name, double fallback, double min, double max,
                    bool min_is_exclusive = false) const;

 private:
  std::vector<std::pair<std::string, std::string>> values_;  // flag name, value ("" for switches)
  std::vector<std::string> positionals_;
};

// Flags every command that extracts shares, and the options they set (defaults from
// ExtractorOptions, never repeated here).
std::vector<FlagSpec> extractor_flags();
ExtractorOptions extractor_options(const Args& args);
std::string extractor_flags_help();

// aief match --pairs: matching of an HDF5 features file (tools/cmd_sfm.cpp).
int run_match_pairs(const Args& args, const MatchOptions& match_options);

}  // namespace aief::cli

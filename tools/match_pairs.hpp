#pragma once
// aief match --pairs (tools/cmd_match.cpp parses the command line): matching of an HDF5 features
// file, pair by pair, into matches.h5.
#include "aief/match.hpp"
#include "tools/cli_args.hpp"

namespace aief::cli {

// The pairs of --pairs matched from `features_file` (HDF5) into -o, with `match_options`.
int run_match_pairs(const Args& args, const std::string& features_file,
                    const MatchOptions& match_options);

}  // namespace aief::cli

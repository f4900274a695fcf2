#pragma once
// The aief subcommands. Each takes the arguments after its name and returns the exit status;
// errors are thrown (cli::UsageError: status 2, aief::Error and others: status 1) and printed
// by main as "aief: error: ...".
#include <string>
#include <vector>

namespace aief::cli {

using Arguments = std::vector<std::string>;

int run_extract(const Arguments& args);
int run_match(const Arguments& args);
int run_adapt(const Arguments& args);
int run_eval(const Arguments& args);
int run_bench(const Arguments& args);
int run_validate(const Arguments& args);
int run_merge(const Arguments& args);  // tools/cmd_sfm.cpp
int run_colmap(const Arguments& args);

}  // namespace aief::cli

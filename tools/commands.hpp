#pragma once
// The aief subcommands, one per tools/cmd_<name>.cpp, listed by tools/main.cpp's kCommands
// (CONTRIBUTING.md, "Adding a command"). Each takes the arguments after its name and returns the
// exit status; errors are thrown (cli::UsageError: status 2, aief::Error and others: status 1) and
// printed by main as "aief: error: ...".
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
int run_merge(const Arguments& args);
int run_colmap(const Arguments& args);

// What a command that needs HDF5 says in a build without it.
inline constexpr const char* kBuiltWithoutHdf5 =
    "this aief was built without HDF5 (install libhdf5-dev and rebuild)";

}  // namespace aief::cli

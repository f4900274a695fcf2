#pragma once
// A file a command writes in one format (`match -o` JSON, `adapt -o` JSON, `match --pairs -o`
// HDF5), checked before any work: a name whose extension says another format is a usage error
// (exit 2), so `-o m.npz` never holds JSON. Pictures: tools/picture_flags.hpp.
#include <string>
#include <string_view>

#include "tools/cli_args.hpp"

namespace aief::cli {

// Throws UsageError when FLAG is given and its path does not end in `extension` (".json").
void check_output_extension(const Args& args, const std::string& flag, std::string_view extension,
                            std::string_view format);

}  // namespace aief::cli

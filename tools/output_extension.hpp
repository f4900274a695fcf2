#pragma once
// A file a command writes in one format (`match -o` JSON, `adapt -o` JSON, `match --pairs -o`
// HDF5, `merge -o` HDF5, `colmap -o` a COLMAP database), checked before any work: a name whose
// extension says another format is a usage error (exit 2), so `-o m.npz` never holds JSON; and
// the folder it goes in. Pictures: tools/picture_flags.hpp.
#include <string>
#include <string_view>

#include "tools/cli_args.hpp"

namespace aief::cli {

// Throws aief::Error (exit 1) when FLAG is given and names a file in a folder that does not
// exist: said before any work (`-o nodir/x.json` failed after the work, naming a temporary file).
void check_output_folder(const Args& args, const std::string& flag);

// Throws UsageError when FLAG is given and its path does not end in `extension` (".json").
void check_output_extension(const Args& args, const std::string& flag, std::string_view extension,
                            std::string_view format);

}  // namespace aief::cli

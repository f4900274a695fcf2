#pragma once
// The picture a command writes at its end (`--draw`, `--plot`), checked before any work: an
// extension OpenCV cannot encode is a usage error (exit 2), a folder that does not exist an
// input error (exit 1), both named before the images are read.
#include <string>

#include "tools/cli_args.hpp"

namespace aief::cli {

void check_picture_flag(const Args& args, const std::string& flag);

}  // namespace aief::cli

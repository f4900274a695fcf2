#pragma once
// Every file a command writes (`-o`, `--draw`, `--plot`, eval's report) checked against the
// images it reads, before any work: a command never writes over one of its inputs. Two paths
// are the same file when they name the same device and inode, so `./x.png` and `x.png`, a hard
// link and a symbolic link to the input are all caught; an output that does not exist yet
// cannot be an input.
#include <string>
#include <vector>

#include "tools/cli_args.hpp"

namespace aief::cli {

struct OutputPath {
  std::string flag;  // "--draw", "-o"
  std::string path;
};

// Throws UsageError (exit 2) naming the flag, the output and the input it would replace.
void refuse_outputs_that_are_inputs(const std::vector<OutputPath>& outputs,
                                    const std::vector<std::string>& inputs);
// The same for the output flags given among `flags` ("--output", "--draw", ...).
void refuse_outputs_that_are_inputs(const Args& args, const std::vector<std::string>& flags,
                                    const std::vector<std::string>& inputs);

}  // namespace aief::cli

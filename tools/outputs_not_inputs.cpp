#include "tools/outputs_not_inputs.hpp"

#include <sys/stat.h>

namespace aief::cli {

namespace {

bool same_file(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

}  // namespace

void refuse_outputs_that_are_inputs(const std::vector<OutputPath>& outputs,
                                    const std::vector<std::string>& inputs) {
  for (const OutputPath& output : outputs) {
    struct stat written {};
    if (::stat(output.path.c_str(), &written) != 0) continue;  // not there yet: no input
    for (const std::string& input : inputs) {
      struct stat read {};
      if (::stat(input.c_str(), &read) != 0 || !same_file(written, read)) continue;
      const std::string how = output.path == input ? "" : " (the same file by another name)";
      throw UsageError(output.flag + " " + output.path + ": it would replace the input '" + input +
                       "'" + how + "; aief never writes over its inputs: choose another name");
    }
  }
}

void refuse_outputs_that_are_inputs(const Args& args, const std::vector<std::string>& flags,
                                    const std::vector<std::string>& inputs) {
  std::vector<OutputPath> outputs;
  for (const std::string& flag : flags)
    if (const auto path = args.get(flag))
      outputs.push_back({flag == "--output" ? "-o" : flag, *path});
  refuse_outputs_that_are_inputs(outputs, inputs);
}

}  // namespace aief::cli

#pragma once
// The built tool run through the shell, for the CLI tests that tests/CMakeLists.txt gives
// AIEF_CLI_PATH (tests/test_option_table.cpp, test_option_resolution.cpp).
#include <string>

#include "tests/test_support.hpp"

namespace aief::test {

using CliResult = aief::test::CommandRun;  // status, and stdout + stderr

// `aief <arguments>`, the arguments split and quoted by sh.
inline CliResult run_cli(const std::string& arguments) {
  return aief::test::run_shell(std::string(AIEF_CLI_PATH) + " " + arguments);
}

}  // namespace aief::test

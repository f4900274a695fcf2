// A command's own flags are written once, in its FlagSpec list with their --help text
// (tools/cli_args.hpp): help_of makes the --help lines from it, laid out as the option rows' lines,
// and Args refuses a flag given twice by either spelling.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tools/cli_args.hpp"

namespace aief::cli {
namespace {

TEST(CliFlagHelp, LinesAreMadeFromTheSpecInTheRowsLayout) {
  const std::vector<FlagSpec> flags = {
      {"--output", "-o", true, "FILE", "matches as JSON"},
      {"--adaptive", "", false, "", "choose F by the sweep"},
      {"--features-file", "--features", true, "FILE", "the HDF5 file"},
      {"--help", "-h", false},  // no help text: listed elsewhere
  };
  EXPECT_EQ(help_of(flags),
            "  -o, --output FILE     matches as JSON\n"
            "  --adaptive            choose F by the sweep\n"
            // An earlier spelling is no short form; a label reaching column 24 ends its line.
            "  --features-file FILE  the HDF5 file\n");
  const std::vector<FlagSpec> long_label = {
      {"--fast-min-threshold", "", true, "T", "retry threshold"}};
  EXPECT_EQ(help_of(long_label),
            "  --fast-min-threshold T\n" + std::string(24, ' ') + "retry threshold\n");
}

TEST(CliFlagHelp, TextIsWrappedAt100ColumnsKeepingLinesAndCommands) {
  std::string words;
  for (int i = 0; i < 20; ++i) words += "word ";  // 15 fit on the first line
  const std::string command =
      "  --shard $((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN))/"
      "$SLURM_ARRAY_TASK_COUNT_AND_MORE_TO_PASS_100_COLUMNS";
  const std::string help =
      help_of({{"--shard", "", true, "i/n", words + "\nSlurm:\n" + command + "\nend"}});
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < help.size();) {
    const std::size_t end = help.find('\n', start);
    lines.push_back(help.substr(start, end - start));
    start = end + 1;
  }
  ASSERT_EQ(lines.size(), 5u) << help;
  EXPECT_EQ(lines[0].rfind("  --shard i/n           word word", 0), 0u) << help;
  EXPECT_LE(lines[0].size(), 100u);
  EXPECT_EQ(lines[1], std::string(24, ' ') + "word word word word word");
  EXPECT_EQ(lines[2], std::string(24, ' ') + "Slurm:");
  EXPECT_EQ(lines[3], std::string(24, ' ') + command.substr(2));  // whole, past 100 columns
  EXPECT_EQ(lines[4], std::string(24, ' ') + "end");
}

TEST(CliFlagHelp, AFlagGivenTwiceIsRefusedNamingBothSpellings) {
  const std::vector<FlagSpec> spec = {{"--output", "-o", true, "FILE", "out"},
                                      {"--draw", "", true, "FILE", "picture"}};
  EXPECT_NO_THROW(Args({"-o", "a.json", "--draw", "p.png"}, spec));
  try {
    Args({"-o", "a.json", "--output=b.json"}, spec);
    ADD_FAILURE() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(),
                 "-o and --output are two spellings of one option, both given: give it once");
  }
  try {
    Args({"--draw", "p.png", "--draw", "q.png"}, spec);
    ADD_FAILURE() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "--draw is given twice: give it once");
  }
}

}  // namespace
}  // namespace aief::cli

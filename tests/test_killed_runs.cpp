// Runs of the CLI that write HDF5, killed for real (kill -9, and SIGTERM, SIGINT, SIGHUP as Slurm's
// time limit, Ctrl-C and a closed terminal send them) in their first images or pairs, before the
// first batch of writes: the file must open, and the same command run again must resume and
// finish (docs/robustness.md: "a kill -9 loses at most the last 64 groups").
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/test_support.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif

#ifdef AIEF_HAVE_HDF5

namespace {

namespace fs = std::filesystem;

// Runs the CLI with `arguments`, and once `watched` exists and is not empty (the run has begun
// writing it), sends it `signal`. Returns the wait status.
int run_and_signal(const std::vector<std::string>& arguments, const std::string& watched,
                   int signal) {
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, SIG_DFL);
    std::vector<char*> argv{const_cast<char*>(AIEF_CLI_PATH)};
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(AIEF_CLI_PATH, argv.data());
    ::_exit(127);
  }
  struct stat status {};
  int waited = 0;
  // Polled, not timed: the signal goes as soon as the first bytes are there.
  while (::stat(watched.c_str(), &status) != 0 || status.st_size == 0) {
    if (::waitpid(child, &waited, WNOHANG) == child) return waited;  // ended before writing
    ::usleep(500);
  }
  ::kill(child, signal);
  ::waitpid(child, &waited, 0);
  return waited;
}

std::vector<std::string> run_words(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  for (char c : line + " ") {
    if (c != ' ') {
      word += c;
    } else if (!word.empty()) {
      words.push_back(word);
      word.clear();
    }
  }
  return words;
}

class KilledRuns : public ::testing::TestWithParam<int> {
 protected:
  // `count` images (one small sample, hard-linked under distinct names): each takes a few
  // milliseconds, the whole batch far longer than the first 64.
  std::string images(int count) {
    const fs::path folder = work_.path() / "images";
    fs::create_directories(folder);
    const std::string sample = aief::test::sample_path("graf", "img1_center_320x240.pgm");
    for (int i = 0; i < count; ++i) {
      std::string name = std::to_string(1000 + i);
      fs::create_hard_link(sample, folder / name.append(".pgm"));
    }
    return folder.string();
  }
  int names_in(const std::string& h5) {
    const aief::io::Hdf5File file(h5, aief::io::Hdf5File::Mode::read);
    return static_cast<int>(file.feature_names().size());
  }
  aief::test::TempFolder work_{"aief_killed_runs"};
};

TEST_P(KilledRuns, ABatchKilledInItsFirstImagesLeavesAFileThatOpensAndResumes) {
  const int signal = GetParam();
  const std::string folder = images(384), h5 = work_.file("kb.h5");
  const std::string command =
      "extract --batch " + folder + " -o " + h5 + " --format h5 --threads 1";
  const int status = run_and_signal(run_words(command), h5, signal);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
      << "the batch was not stopped by signal " << signal << " (status " << status << ")";
  int kept = -1;
  ASSERT_NO_THROW(kept = names_in(h5)) << "the killed run left a file that does not open";
  EXPECT_LT(kept, 64);
  const aief::test::CommandRun rerun =
      aief::test::run_shell(std::string(AIEF_CLI_PATH) + " " + command);
  ASSERT_EQ(rerun.status, 0) << rerun.output;
  EXPECT_NE(rerun.output.find(std::to_string(kept) + " already done"), std::string::npos)
      << rerun.output;
  EXPECT_EQ(names_in(h5), 384);
}

TEST_P(KilledRuns, MatchPairsKilledInItsFirstPairsLeavesAFileThatOpensAndResumes) {
  const int signal = GetParam();
  const std::string folder = images(40), features = work_.file("f.h5"),
                    matches = work_.file("m.h5"), pairs = work_.file("pairs.txt");
  ASSERT_EQ(aief::test::run_shell(std::string(AIEF_CLI_PATH) + " extract --batch " + folder +
                                  " -o " + features + " --format h5")
                .status,
            0);
  int count = 0;
  {
    std::ofstream list(pairs);
    for (int i = 0; i < 40; ++i)
      for (int j = i + 1; j < 40; ++j, ++count) list << 1000 + i << ".pgm " << 1000 + j << ".pgm\n";
  }
  const std::string command =
      "match --pairs " + pairs + " --features " + features + " -o " + matches;
  const int status = run_and_signal(run_words(command), matches, signal);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
      << "the match was not stopped by signal " << signal << " (status " << status << ")";
  ASSERT_NO_THROW(aief::io::Hdf5File(matches, aief::io::Hdf5File::Mode::read))
      << "the killed run left a file that does not open";
  const aief::test::CommandRun rerun =
      aief::test::run_shell(std::string(AIEF_CLI_PATH) + " " + command);
  ASSERT_EQ(rerun.status, 0) << rerun.output;
  const aief::io::Hdf5File file(matches, aief::io::Hdf5File::Mode::read);
  for (int i = 0; i < 40; ++i)
    for (int j = i + 1; j < 40; ++j)
      EXPECT_TRUE(
          file.has_matches(std::to_string(1000 + i) + ".pgm", std::to_string(1000 + j) + ".pgm"));
  EXPECT_EQ(count, 780);
}

INSTANTIATE_TEST_SUITE_P(EverySignal, KilledRuns,
                         ::testing::Values(SIGKILL, SIGTERM, SIGINT, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) {
                           switch (info.param) {
                             case SIGKILL: return std::string("SIGKILL");
                             case SIGTERM: return std::string("SIGTERM");
                             case SIGINT: return std::string("SIGINT");
                             default: return std::string("SIGHUP");
                           }
                         });

}  // namespace

#endif  // AIEF_HAVE_HDF5

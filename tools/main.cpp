// aief: the command line. One subcommand per file (tools/cmd_*.cpp).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iomanip>
#include <iostream>
#include <string_view>
#include <vector>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "aief/version.hpp"
#include "simd/kernels.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"

namespace {

struct Command {
  std::string_view name;
  std::string_view summary;
  int (*run)(const aief::cli::Arguments&);
};

constexpr Command kCommands[] = {
    {"extract", "keypoints and descriptors of one image (or a batch)", aief::cli::run_extract},
    {"match", "match two images, RANSAC homography, optional adaptive F", aief::cli::run_match},
    {"adapt", "sweep the entropy threshold F over a pair, print the curve", aief::cli::run_adapt},
    {"eval", "the paper's tables and ground-truth metrics on the Oxford dataset",
     aief::cli::run_eval},
    {"bench", "median milliseconds per stage on your image, beside cv::ORB", aief::cli::run_bench},
    {"validate", "every SIMD kernel against the scalar reference on this CPU",
     aief::cli::run_validate},
    {"merge", "merge the shards' HDF5 feature files into one", aief::cli::run_merge},
    {"colmap", "a COLMAP database from HDF5 features and matches", aief::cli::run_colmap},
};

void print_usage(std::ostream& out) {
  out << "usage: aief <command> [options]   (aief <command> --help for its options)\n\ncommands:\n";
  for (const Command& c : kCommands)
    out << "  " << c.name << std::string(10 - c.name.size(), ' ') << c.summary << "\n";
  out << "\n  --print-kernels  the kernel sets this CPU runs, the one chosen by default, each "
         "kernel's code\n"
      << "  --version        the version\n"
      << "\nenvironment:\n  AIEF_KERNELS     the kernel set `auto` stands for: scalar, sse4.2, "
         "avx2, avx512, neon64 or auto\n";
}

// The sets this CPU runs, the one `auto` picks (and why), and which code each kernel of each set
// runs: the AVX-512 table mixes 512-bit kernels with 256-bit ones, and VPOPCNTDQ swaps one in.
int print_kernels() {
  const std::vector<aief::KernelSet> sets = aief::available_kernel_sets();
  const aief::KernelSet chosen = aief::default_kernel_set();  // throws on a bad AIEF_KERNELS
  const char* forced = std::getenv(aief::kKernelsEnvironmentVariable);
  const std::string why = forced != nullptr && *forced != '\0'
                              ? std::string(aief::kKernelsEnvironmentVariable) + "=" + forced
                              : std::string("the best this CPU runs; ") +
                                    aief::kKernelsEnvironmentVariable + " forces another";
  std::cout << "available:";
  for (aief::KernelSet set : sets) std::cout << ' ' << aief::to_string(set);
  std::cout << "\ndefault: " << aief::to_string(chosen) << " (" << why
            << ")\n\nthe code each set runs:\n";
  constexpr int kNameWidth = 25, kColumnWidth = 25;
  std::cout << std::left << std::setw(kNameWidth) << "kernel";
  for (std::size_t i = 0; i < sets.size(); ++i)
    std::cout << std::setw(i + 1 < sets.size() ? kColumnWidth : 0) << aief::to_string(sets[i]);
  std::cout << "\n";
  for (int k = 0; k < aief::kKernelCount; ++k) {
    std::cout << std::setw(kNameWidth) << aief::kKernelNames[k];
    for (std::size_t i = 0; i < sets.size(); ++i)
      std::cout << std::setw(i + 1 < sets.size() ? kColumnWidth : 0)
                << aief::kernel_variant(aief::kernel_table(sets[i]), k);
    std::cout << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string_view first = argc > 1 ? argv[1] : "";
  try {
    if (first.empty() || first == "--help" || first == "-h" || first == "help") {
      print_usage(first.empty() ? std::cerr : std::cout);
      return first.empty() ? 2 : 0;
    }
    if (first == "--print-kernels" || first == "--version") {
      if (argc > 2)
        throw aief::cli::UsageError(std::string(first) + " takes no argument, got '" + argv[2] +
                                    "'");
      if (first == "--print-kernels") return print_kernels();
      std::cout << "aief " << aief::kVersionString << "\n";
      return 0;
    }
    for (const Command& command : kCommands) {
      if (command.name != first) continue;
      return command.run(aief::cli::Arguments(argv + 2, argv + argc));
    }
    throw aief::cli::UsageError("unknown command '" + std::string(first) +
                                "' (aief --help lists them)");
  } catch (const aief::cli::UsageError& e) {
    std::cerr << "aief: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "aief: error: " << e.what() << "\n";
    return 1;
  }
}

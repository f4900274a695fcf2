// aief merge -o features.h5 shard0.h5 shard1.h5 ... (io/hdf5_merge.hpp)
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "aief/error.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/output_extension.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_merge.hpp"
#endif

namespace aief::cli {

int run_merge(const Arguments& arguments) {
  const Args args(arguments, {{"--output", "-o", true}, {"--help", "-h", false}});
  if (args.has("--help")) {
    std::cout
        << "usage: aief merge -o FEATURES.h5 SHARD.h5...\n\n"
        << "Copies the image groups of the shards' feature files (aief extract --batch --format h5 "
           "--shard i/n)\n"
        << "into one file; images already in it are kept, an image in two shards is an error.\n";
    return 0;
  }
  const auto output = args.get("--output");
  if (!output || args.positionals().empty())
    throw UsageError("merge expects -o FEATURES.h5 and one or more shard files");
  check_output_extension(args, "--output", ".h5", "a features file in HDF5 (hloc's layout)");
  check_output_folder(args, "--output");
#ifdef AIEF_HAVE_HDF5
  int replaced = 0;
  std::vector<std::string> notes;
  const int copied = io::merge_feature_files(*output, args.positionals(), &replaced, &notes);
  for (const std::string& note : notes) std::cerr << "aief: note: " << note << "\n";
  std::printf("%d images merged into %s", copied, output->c_str());
  if (replaced > 0)
    std::printf(" (%d replacing what it held of them: their image or options changed)", replaced);
  std::printf("\n");
  return 0;
#else
  throw Error(kBuiltWithoutHdf5);
#endif
}

}  // namespace aief::cli

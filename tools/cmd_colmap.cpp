// aief colmap --features-file features.h5 --matches matches.h5 --pairs pairs.txt -o database.db
// (io/colmap_database.hpp)
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "aief/error.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#include "tools/output_extension.hpp"
#ifdef AIEF_HAVE_COLMAP_EXPORT
#include "io/colmap_database.hpp"
#include "io/utf8.hpp"
#endif

namespace aief::cli {

int run_colmap(const Arguments& arguments) {
  const Args args(arguments, {{"--features-file", "--features", true},
                              {"--matches", "", true},
                              {"--pairs", "", true},
                              {"--output", "-o", true},
                              {"--help", "-h", false}});
  if (args.has("--help")) {
    std::cout
        << "usage: aief colmap --features-file FEATURES.h5 --matches MATCHES.h5 "
           "--pairs PAIRS.txt -o DATABASE.db\n\n"
        << "A COLMAP database (cameras, images, keypoints, descriptors, matches) "
           "from aief's hloc files, for\n"
        << "  colmap matches_importer --database_path DATABASE.db "
           "--match_list_path PAIRS.txt --match_type pairs\n"
        << "  colmap mapper --database_path DATABASE.db --image_path IMAGES --output_path SPARSE\n"
        << "Keypoints are shifted by +0.5 px to COLMAP's origin (the top-left pixel's corner).\n"
        << "(--features, the earlier spelling of --features-file, is still accepted.)\n";
    return 0;
  }
  const auto features = args.get("--features-file"), matches = args.get("--matches"),
             pairs = args.get("--pairs"), output = args.get("--output");
  if (!features || !matches || !pairs || !output)
    throw UsageError(
        "colmap expects --features-file FEATURES.h5 --matches MATCHES.h5 --pairs PAIRS.txt -o "
        "DATABASE.db");
  // An input given as -o is named as such, as match --pairs does, before the extension is asked.
  struct Input {
    const char* flag;
    const char* what;
    const std::string& path;
  };
  for (const Input& input :
       {Input{"--features-file", "features file", *features},
        Input{"--matches", "matches file", *matches}, Input{"--pairs", "pairs file", *pairs}})
    if (std::error_code ec; std::filesystem::equivalent(input.path, *output, ec))
      throw Error("-o '" + *output + "' is the " + input.what + " (" + input.flag + " '" +
                  input.path +
                  "'): the COLMAP database goes to a file of its own (DATABASE.db); nothing was "
                  "written");
  check_output_extension(args, "--output", ".db", "a COLMAP database (SQLite)");
  check_output_folder(args, "--output");
#ifdef AIEF_HAVE_COLMAP_EXPORT
  const io::ColmapExport done = io::export_colmap_database(*output, *features, *matches, *pairs);
  for (const std::string& note : done.notes) std::cerr << "aief: note: " << note << "\n";
  std::printf("COLMAP database %s: %d images, %d pairs, %lld matches\n", output->c_str(),
              done.images, done.pairs, done.matches);
  if (!done.names_not_utf8.empty())
    std::cerr << "aief: note: " << done.names_not_utf8.size()
              << " image name(s) are not UTF-8 (the first: '"
              << io::escape_non_utf8(done.names_not_utf8.front())
              << "'): stored as their bytes, as COLMAP stores them; Python's sqlite3 "
              << "reads them with connection.text_factory = bytes\n";
  return 0;
#else
  throw Error(
      "this aief was built without SQLite or HDF5 (install libsqlite3-dev libhdf5-dev and "
      "rebuild)");
#endif
}

}  // namespace aief::cli

// Feature files for SfM tools (io/hdf5_file.hpp, io/colmap_database.hpp):
//   aief match --pairs pairs.txt --features features.h5 -o matches.h5 [--matcher K] [--ratio R]
//   aief merge -o features.h5 shard0.h5 shard1.h5 ...
//   aief colmap --features features.h5 --matches matches.h5 --pairs pairs.txt -o database.db
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "tools/cli_args.hpp"
#include "tools/commands.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_descriptor_cache.hpp"
#include "io/hdf5_file.hpp"
#include "io/hdf5_merge.hpp"
#include "io/match_record.hpp"
#include "io/option_record.hpp"
#include "io/pairs_file.hpp"
#endif
#ifdef AIEF_HAVE_COLMAP_EXPORT
#include "io/colmap_database.hpp"
#include "io/utf8.hpp"
#endif

namespace aief::cli {

namespace {

[[maybe_unused]] const char* const kNoHdf5 =
    "this aief was built without HDF5 (install libhdf5-dev and rebuild)";
// Descriptors kept in memory by match --pairs: about 16k images of 2000 features.
[[maybe_unused]] constexpr std::size_t kDescriptorCacheBytes = std::size_t{1} << 30;

// "with other options or features (kind mutual -> ratio; the features of 'a.png': ...)": the
// first reasons, so that a million re-extracted images make one line.
[[maybe_unused]] std::string redone_reasons(const std::vector<std::string>& reasons) {
  constexpr std::size_t kShown = 4;
  std::string text;
  for (std::size_t i = 0; i < reasons.size() && i < kShown; ++i)
    text += (i > 0 ? "; " : "") + reasons[i];
  if (reasons.size() > kShown) text += "; and " + std::to_string(reasons.size() - kShown) + " more";
  return "otherwise (" + text + ")";
}

}  // namespace

int run_match_pairs(const Args& args, const MatchOptions& match_options) {
#ifdef AIEF_HAVE_HDF5
  const auto features_path = args.get("--features");
  const auto output = args.get("--output");
  if (!features_path || !output)
    throw UsageError("--pairs needs --features FEATURES.h5 and -o MATCHES.h5");
  if (!args.positionals().empty())
    throw UsageError("--pairs takes its images from the pairs file, not from positional arguments");
  const io::PairsList pairs = io::read_pairs(*args.get("--pairs"));
  for (const std::string& note : pairs.notes) std::cerr << "aief: note: " << note << "\n";
  if (std::error_code ec; std::filesystem::equivalent(*features_path, *output, ec))
    throw Error("-o '" + *output + "' is the features file (--features '" + *features_path +
                "'): matches go to a file of their own (hloc's matches.h5); nothing was written");
  const io::Hdf5File features(*features_path, io::Hdf5File::Mode::read);
  io::Hdf5File matches_file(*output, io::Hdf5File::Mode::read_write);
  if (const std::string& image = matches_file.first_image_group(); !image.empty())
    throw Error("-o '" + *output + "' holds features (image '" + image +
                "'): matches go to a file of their own (hloc's matches.h5); nothing was written");
  io::DescriptorCache descriptors(features, kDescriptorCacheBytes);
  io::PairRecords records(features, match_options);
  int written = 0, skipped = 0, redone = 0;
  std::vector<std::string> redone_for;  // each reason once
  long long total = 0;
  for (std::size_t pair = 0; pair < pairs.size(); ++pair) {
    const std::string &name0 = pairs.name0(pair), &name1 = pairs.name1(pair);
    const io::PairRecord record = records.of(name0, name1);
    require_same_descriptor(io::recorded_descriptor(record.options0), "'" + name0 + "'",
                            io::recorded_descriptor(record.options1),
                            "'" + name1 + "' (both in '" + *features_path + "')");
    if (matches_file.has_matches(name0, name1)) {  // a resumed run: kept only if made as now
      const std::vector<std::string> changes =
          io::pair_changes(matches_file.pair_record(name0, name1), record, name0, name1);
      if (changes.empty()) {
        ++skipped;
        continue;
      }
      ++redone;
      for (const std::string& change : changes)
        if (std::find(redone_for.begin(), redone_for.end(), change) == redone_for.end())
          redone_for.push_back(change);
    }
    const auto a = descriptors.get(name0), b = descriptors.get(name1);
    const std::vector<Match> matches = match_descriptors(*a, *b, match_options);
    matches_file.write_matches(name0, name1, static_cast<int>(a->size()), matches, &record);
    ++written;
    total += static_cast<long long>(matches.size());
  }
  matches_file.close();  // the last batch of pairs flushed, or an error
  std::printf("%d pairs matched (%s), %lld matches, %d already in %s; %zu images read\n", written,
              std::string(to_string(match_options.kind)).c_str(), total, skipped, output->c_str(),
              descriptors.reads());
  if (redone > 0)
    std::cerr << "aief: note: " << redone << " pairs of " << *output
              << " matched again, since they were matched " << redone_reasons(redone_for) << "\n";
  return 0;
#else
  (void)args;
  (void)match_options;
  throw Error(kNoHdf5);
#endif
}

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
#ifdef AIEF_HAVE_HDF5
  int replaced = 0;
  const int copied = io::merge_feature_files(*output, args.positionals(), &replaced);
  std::printf("%d images merged into %s", copied, output->c_str());
  if (replaced > 0)
    std::printf(" (%d replacing what it held of them: their image or options changed)", replaced);
  std::printf("\n");
  return 0;
#else
  throw Error(kNoHdf5);
#endif
}

int run_colmap(const Arguments& arguments) {
  const Args args(arguments, {{"--features", "", true},
                              {"--matches", "", true},
                              {"--pairs", "", true},
                              {"--output", "-o", true},
                              {"--help", "-h", false}});
  if (args.has("--help")) {
    std::cout
        << "usage: aief colmap --features FEATURES.h5 --matches MATCHES.h5 --pairs PAIRS.txt -o "
           "DATABASE.db\n\n"
        << "A COLMAP database (cameras, images, keypoints, descriptors, matches) from aief's hloc "
           "files, for\n"
        << "  colmap matches_importer --database_path DATABASE.db --match_list_path PAIRS.txt "
           "--match_type pairs\n"
        << "  colmap mapper --database_path DATABASE.db --image_path IMAGES --output_path SPARSE\n"
        << "Keypoints are shifted by +0.5 px to COLMAP's origin (the top-left pixel's corner).\n";
    return 0;
  }
  const auto features = args.get("--features"), matches = args.get("--matches"),
             pairs = args.get("--pairs"), output = args.get("--output");
  if (!features || !matches || !pairs || !output)
    throw UsageError(
        "colmap expects --features FEATURES.h5 --matches MATCHES.h5 --pairs PAIRS.txt -o "
        "DATABASE.db");
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

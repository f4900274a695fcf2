// aief match --pairs: the pairs of an hloc pairs file matched from an HDF5 features file into
// matches.h5 (io/hdf5_file.hpp), resumable (io/match_record.hpp).
#include "tools/match_pairs.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "tools/commands.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_feature_cache.hpp"
#include "io/hdf5_file.hpp"
#include "io/match_record.hpp"
#include "io/option_record.hpp"
#include "io/pairs_file.hpp"
#endif

namespace aief::cli {

namespace {

// Features kept in memory by match --pairs: about 16k images of 2000 descriptors (about 9.6k with
// their keypoints, for --matcher guided).
[[maybe_unused]] constexpr std::size_t kFeatureCacheBytes = std::size_t{1} << 30;

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

int run_match_pairs(const Args& args, const std::string& features_file,
                    const MatchOptions& match_options) {
#ifdef AIEF_HAVE_HDF5
  const std::string* features_path = &features_file;
  const auto output = args.get("--output");
  if (!args.positionals().empty())
    throw UsageError("--pairs takes its images from the pairs file, not from positional arguments");
  const io::PairsList pairs = io::read_pairs(*args.get("--pairs"));
  for (const std::string& note : pairs.notes) std::cerr << "aief: note: " << note << "\n";
  if (std::error_code ec; std::filesystem::equivalent(*features_path, *output, ec))
    throw Error("-o '" + *output + "' is the features file (--features-file '" + *features_path +
                "'): matches go to a file of their own (hloc's matches.h5); nothing was written");
  const io::Hdf5File features(*features_path, io::Hdf5File::Mode::read);
  io::Hdf5File matches_file(*output, io::Hdf5File::Mode::read_write);
  if (const std::string& image = matches_file.first_image_group(); !image.empty())
    throw Error("-o '" + *output + "' holds features (image '" + image +
                "'): matches go to a file of their own (hloc's matches.h5); nothing was written");
  io::FeatureCache cache(features, kFeatureCacheBytes, match_options.kind == MatcherKind::guided);
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
    const auto a = cache.get(name0), b = cache.get(name1);
    const std::vector<Match> matches = match_features(*a, *b, match_options);
    matches_file.write_matches(name0, name1, static_cast<int>(a->descriptors.size()), matches,
                               &record);
    ++written;
    total += static_cast<long long>(matches.size());
  }
  matches_file.close();  // the last batch of pairs flushed, or an error
  std::printf("%d pairs matched (%s), %lld matches, %d already in %s; %zu images read\n", written,
              std::string(to_string(match_options.kind)).c_str(), total, skipped, output->c_str(),
              cache.reads());
  if (redone > 0)
    std::cerr << "aief: note: " << redone << " pairs of " << *output
              << " matched again, since they were matched " << redone_reasons(redone_for) << "\n";
  return 0;
#else
  (void)args;
  (void)features_file;
  (void)match_options;
  throw Error(kBuiltWithoutHdf5);
#endif
}

}  // namespace aief::cli

#pragma once
// `aief extract --batch LIST|DIR -o OUTDIR`: many images through a TBB pipeline (read, extract,
// write overlap), resumable, shardable.
//
// Names. Each input has a name, its key (hloc's and COLMAP's convention): its path below DIR as
// listed, or the line of LIST, with "." parts and doubled '/' dropped. Symlinks are never
// resolved: two links to one file are two inputs with two outputs. Its output is
// OUTDIR/<name>.<format> with the name's folders mirrored (`sub/x.png` -> `OUTDIR/sub/x.png.json`);
// the only rewrites keep the name inside OUTDIR and stay one-to-one: '%' -> "%25", a ".." part ->
// "%2E%2E", a leading '/' -> a first folder "%2F". So no two inputs share an output.
//
// HDF5 (--format h5): one file, a group per input named by the same name (hloc's features.h5).
//
// Resume. Every output records its input's name, size and modification time; a run skips an
// input whose output holds exactly that record and extracts the others again (a changed image,
// an output cut short). Outputs appear atomically (temporary file, then rename); a run first
// removes the stale temporary a killed run left for each of its outputs.
//
// Shards. --shard i/n takes images i, i+n, i+2n ... of the list sorted by name, 0 <= i < n:
// machines split a collection with no coordinator.
#include <optional>
#include <string>
#include <vector>

#include "aief/options.hpp"
#include "io/features_files.hpp"

namespace aief::cli {

struct BatchSettings {
  std::string input;        // a folder (its images, recursively) or a text file of paths, one per line
  std::string output_dir;       // for format h5: the HDF5 file
  std::string format = "json";  // json | yml | npz (a file per image: the output extension) | h5 (one hloc file, io/hdf5_features.hpp)
  int shard_index = 0, shard_count = 1;
  ExtractorOptions options;
};

struct BatchSummary {
  int images = 0;     // in this shard
  int extracted = 0;
  int replaced = 0;   // of those extracted: the output was there but from another or changed input
  int skipped = 0;    // output already complete and of this very input
  int failed = 0;
  long long keypoints = 0;
  std::vector<std::string> failures;  // "path: reason"
};

// One image of a batch.
struct BatchInput {
  std::string path;  // where it is read: DIR/name, or the list line as written
  std::string name;  // its key (see above)
};

// "i/n" -> {i, n}; throws aief::Error naming the rule (0 <= i < n <= 2^31 - 1) and the 1-based recipe.
struct Shard {
  int index = 0, count = 1;
};
Shard parse_shard(const std::string& text);

// The images of a folder or list file, sorted by name, this shard's only. Throws aief::Error,
// also when two inputs' outputs would clash (a file output where another needs a folder).
std::vector<BatchInput> batch_inputs(const BatchSettings& settings);

// The output file of the input named `name` (see above). One function for every format: a new
// writer reuses the naming, the record check and the temporary-file rule.
std::string batch_output_path(const std::string& output_dir, const std::string& name, const std::string& format);

// Whether an existing output can be kept for this input: it exists and records exactly `source`.
bool batch_output_is_current(const std::string& output, const io::SourceRecord& source);

BatchSummary run_batch(const BatchSettings& settings);

}  // namespace aief::cli

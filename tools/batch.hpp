#pragma once
// `aief extract --batch LIST|DIR -o OUTDIR`: many images through a TBB pipeline (read, extract,
// write overlap), resumable, shardable.
//
// Which images, their names and their output files: io/batch_inputs.hpp and
// io/batch_output_names.hpp (one rule for the CLI, the Python module and the Dask recipe).
//
// HDF5 (--format h5): one file, a group per input named by the same name (hloc's features.h5).
// The pipeline writes through an output sink (tools/batch_sink.hpp) and knows no format.
//
// Failures. An input that cannot be read or extracted fails alone (listed, exit 1, its stale
// output removed); a failure of the output itself (a full disk, an I/O error) stops the batch:
// every output complete before is kept, and the same command resumes once it is fixed.
//
// Resume. Every output records its input's name, size and modification time, and the options it
// was made with (io/option_record.hpp); a run skips an input whose output holds exactly that
// input and options that give the same output (the thread count, say, may differ), and extracts
// the others again (a changed image, an output cut short, other options, an older aief's output
// without an option record). Outputs appear atomically (temporary file, then rename); a run first
// removes the stale temporary a killed run left for each of its outputs.
//
// Shards. --shard i/n takes images i, i+n, i+2n ... of the list sorted by name, 0 <= i < n:
// machines split a collection with no coordinator. Not with --entropy-threshold carried: the frames
// of one video carry F from frame to frame, so a shard's F would differ from one run's (refused).
#include <optional>
#include <string>
#include <vector>

#include "aief/options.hpp"
#include "io/batch_inputs.hpp"
#include "io/feature_formats.hpp"

namespace aief::cli {

struct BatchSettings {
  std::string input;  // a folder (its images, recursively) or a text file of paths, one per line
  std::string output_dir;       // for format h5: the HDF5 file
  std::string format = "json";  // json | yml | npz (a file per image: the output extension) | h5
                                // (one hloc file, io/hdf5_file.hpp)
  int shard_index = 0, shard_count = 1;
  ExtractorOptions options;
};

struct BatchSummary {
  int images = 0;  // in this shard
  int extracted = 0;
  int replaced = 0;  // of those extracted: the output was there but from another or changed input
  int redone = 0;    // of those extracted: the output was of this input but of other options
  std::vector<std::string> redone_for;  // why, each option change once ("n_features 500 -> 3000")
  int skipped = 0;                      // output already complete and of this very input
  // Entries the output holds of none of this run's inputs (deleted or moved images): kept.
  std::vector<std::string> of_no_input;
  int on_disk = 0;  // of those extracted, the outputs the disk holds (fewer after a stop, maybe)
  int failed = 0;
  long long keypoints = 0;
  std::vector<std::string> failures;  // "path: reason"
  // Why the batch stopped before its end: its output failed (a full disk, an I/O error; see
  // tools/batch_sink.hpp). Outputs complete before are kept; empty when it ran through.
  std::string stopped;
};

using io::BatchInput;

// "i/n" -> {i, n}; throws aief::Error naming the rule (0 <= i < n <= 2^31 - 1) and the 1-based
// recipe.
struct Shard {
  int index = 0, count = 1;
};
Shard parse_shard(const std::string& text);

// The images of a folder or list file, sorted by name (with --entropy-threshold carried, in frame
// order, said in a note: io::InputOrder::frames), this shard's only. Throws aief::Error, also when
// two inputs' outputs would clash (io::check_batch_outputs_do_not_nest).
std::vector<BatchInput> batch_inputs(const BatchSettings& settings);

BatchSummary run_batch(const BatchSettings& settings);

}  // namespace aief::cli

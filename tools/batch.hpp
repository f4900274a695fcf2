#pragma once
// `aief extract --batch LIST|DIR -o OUTDIR`: many images through a TBB pipeline (read, extract,
// write overlap), resumable (an image whose output exists is skipped; outputs appear atomically
// by rename, so a killed run never leaves a half file), shardable (--shard i/n takes every n-th
// image from the i-th, of the sorted list: machines split a collection with no coordinator).
#include <string>
#include <vector>

#include "aief/options.hpp"

namespace aief::cli {

struct BatchSettings {
  std::string input;        // a folder (its images, sorted) or a text file of paths, one per line
  std::string output_dir;       // for format h5: the HDF5 file
  std::string format = "json";  // json | yml | npz (a file per image) | h5 (one hloc file, io/hdf5_features.hpp)
  int shard_index = 0, shard_count = 1;
  ExtractorOptions options;
};

struct BatchSummary {
  int images = 0;     // in this shard
  int extracted = 0;
  int skipped = 0;    // output already complete
  int failed = 0;
  long long keypoints = 0;
  std::vector<std::string> failures;  // "path: reason"
};

// The images of a folder or list file, sorted, this shard's only. Throws aief::Error.
std::vector<std::string> batch_inputs(const BatchSettings& settings);
// The output file of one input: its path below the input root, '/' turned to "__", + extension.
std::string batch_output_path(const BatchSettings& settings, const std::string& input);

// The image's name in an h5 file: its path below the input root (as listed for a list file), '/'-separated,
// extension kept, as hloc names images.
std::string batch_image_name(const BatchSettings& settings, const std::string& input);

BatchSummary run_batch(const BatchSettings& settings);

}  // namespace aief::cli

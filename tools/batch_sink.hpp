#pragma once
// Where a batch's features go (tools/batch.hpp): a file per image (json, yml, npz) or one file
// for the batch (h5), as the format's row says (io/feature_formats.hpp). The batch pipeline knows
// nothing of formats; it asks its sink these three things.
#include <memory>
#include <string>
#include <vector>

#include "aief/error.hpp"
#include "aief/features.hpp"
#include "io/feature_formats.hpp"
#include "io/source_record.hpp"
#include "tools/batch.hpp"

namespace aief::cli {

// A failure of the output itself (a full disk, an I/O error, an HDF5 file that refuses further
// writes): the batch stops, keeping every output complete before, rather than fail each image.
class SinkFailure : public Error {
 public:
  using Error::Error;
};

class BatchSink {
 public:
  virtual ~BatchSink() = default;

  struct Existing {
    bool present = false;        // an output of this name is there
    bool of_this_input = false;  // ... and records exactly this input (name, size, modification
                                 // time)
    // ... made with other options than this run's, as far as they change the output
    // (io::option_changes: "n_features 500 -> 3000"; an output without a record has one).
    std::vector<std::string> option_changes;
    // The one rule of resume: an output is kept when it is of this input and of these options.
    bool current() const { return of_this_input && option_changes.empty(); }
  };
  // What is there for `input`. Called from the pipeline's parallel stage, several at a time; may
  // tidy what a killed run left (a stale temporary).
  virtual Existing existing(const BatchInput& input, const io::SourceRecord& source) = 0;
  // Writes one input's features. One call at a time. Throws SinkFailure when the output itself
  // failed, aief::Error when only this input's output did.
  virtual void write(const BatchInput& input, const Features& features,
                     const io::SourceRecord& source) = 0;
  // Removes `input`'s output (one from another or a changed input, beside a failure). One call
  // at a time; best effort: returns what went wrong, empty when nothing did.
  virtual std::string remove(const BatchInput& input) = 0;
  // After the last write: makes every write durable (a file that batches its writes flushes and
  // closes). Throws SinkFailure.
  virtual void finish() {}
  // The names of the entries the output holds that are none of `inputs` (sorted by name): images
  // deleted or moved since an earlier run wrote them, kept, and said in a note. Before finish().
  virtual std::vector<std::string> entries_of_no_input(const std::vector<BatchInput>& inputs) {
    (void)inputs;
    return {};
  }
  // Throws aief::Error, before anything is written, when the output holds entries this run keeps
  // (none of `inputs`: another shard's images, or images gone from the folder) whose descriptor
  // is not this run's: one file would then hold descriptors that never match each other, which
  // merge, match and colmap refuse.
  virtual void refuse_mixed_descriptors(const std::vector<BatchInput>& inputs) { (void)inputs; }
  // Of `written` outputs written, how many the disk holds (a file that batches its writes loses
  // those after its last flush when the disk fills at a flush).
  virtual int written_on_disk(int written) const { return written; }
};

// The sink of settings.format, its output created or opened. Throws aief::Error (a format this
// build lacks, an output that cannot be created).
std::unique_ptr<BatchSink> make_batch_sink(const BatchSettings& settings);

// By the format's layout (io/feature_formats.hpp): one file per image (io::batch_output_path),
// or one file for the batch (io::FeatureCollectionFile; throws when this build lacks it).
std::unique_ptr<BatchSink> make_file_per_image_sink(const BatchSettings& settings,
                                                    const io::FeatureFormat& format);
std::unique_ptr<BatchSink> make_collection_sink(const BatchSettings& settings,
                                                const io::FeatureFormat& format);

}  // namespace aief::cli

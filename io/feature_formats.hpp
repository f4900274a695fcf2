#pragma once
// Every features format, one row each: its --format name, what it is, its extensions, whether it is
// a file per image or one file for a whole batch, its writer, the reader of what a resume checks,
// and which names it cannot hold. The CLI's checks, aief extract --help, the batch's sinks and the
// messages that list formats are made from the rows. A new format is a writer and a row
// (CONTRIBUTING.md, "Adding a file format").
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aief/features.hpp"
#include "aief/options.hpp"
#include "io/source_record.hpp"

namespace aief::io {

// A file that holds a whole batch's features, an entry per image named by its batch name (HDF5:
// a group per image, io/hdf5_file.hpp). One caller at a time.
class FeatureCollectionFile {
 public:
  virtual ~FeatureCollectionFile() = default;
  // Whether `name` has a complete entry.
  virtual bool holds(const std::string& name) const = 0;
  // Whether `name` has a complete entry written from the file `source` describes.
  virtual bool holds_from(const std::string& name, const SourceRecord& source) const = 0;
  // The option record of `name`'s entry (JSON text); nullopt when it has none.
  virtual std::optional<std::string> option_record(const std::string& name) const = 0;
  // Writes `name`'s entry, replacing any. Throws aief::Error; after a failure of the file itself
  // (a full disk) it refuses every later write.
  virtual void write(const std::string& name, const Features& features, const SourceRecord& source,
                     const ExtractorOptions& options) = 0;
  virtual void remove(const std::string& name) = 0;
  // Makes every write durable; throws aief::Error when it cannot.
  virtual void close() = 0;
};

struct FeatureFormat {
  enum class Layout { file_per_image, one_file_per_batch };
  const char* name;                     // --format's value; a file per image's output suffix
  const char* what;                     // for --help: "OpenCV FileStorage YAML"
  std::vector<const char*> extensions;  // lower case, with the dot; the first is the usual one
  Layout layout;
  // A file per image: writes one image's features atomically (temporary, then rename).
  void (*write)(const std::string& path, const std::string& image_path, const Features& features,
                const ExtractorOptions& options, const std::optional<SourceRecord>& source);
  // ... what the file at `path` records of its making (OutputRecord{} when unreadable).
  OutputRecord (*record)(const std::string& path, const SourceRecord& source);
  // ... throws aief::Error when the format cannot hold these names; nullptr: it holds any.
  void (*check_can_hold)(const std::string& image_path, const std::string& source_name);
  // One file per batch: opens (creating when missing) the file. nullptr when this build lacks the
  // library, `missing` says which.
  std::unique_ptr<FeatureCollectionFile> (*open)(const std::string& path);
  const char* missing;
};

// Every format, in the order messages list them.
const std::vector<FeatureFormat>& feature_formats();
// The format --format names, or nullptr.
const FeatureFormat* feature_format_named(const std::string& name);
// The format of a path's extension (any case), or nullptr.
const FeatureFormat* feature_format_of_path(const std::string& path);
// "json, yml, npz or h5": every --format name.
std::string feature_format_names();
// The formats of one layout, in the order messages list them.
std::vector<const FeatureFormat*> feature_formats_of(FeatureFormat::Layout layout);
// ".json, .yml, .yaml or .npz": the extensions of the formats of one layout.
std::string feature_format_extensions(FeatureFormat::Layout layout);

// By the extension of `path`, a file-per-image format's (throws aief::Error for another):
void write_features(const std::string& path, const std::string& image_path,
                    const Features& features, const ExtractorOptions& options,
                    const std::optional<SourceRecord>& source = std::nullopt);
// What the result file `output_path` records: whether it is complete and of `source` (false when
// it is missing, cut short, unreadable, or from another input), and its option record.
OutputRecord features_file_record(const std::string& output_path, const SourceRecord& source);
bool features_file_belongs_to(const std::string& output_path, const SourceRecord& source);
// True when write_features accepts the path's extension: the CLI asks before any work.
bool is_features_file_name(const std::string& path);
// Throws aief::Error when `format` cannot hold these names and read them back, naming the formats
// of its layout that can.
void check_format_can_hold(const FeatureFormat& format, const std::string& image_path,
                           const std::string& source_name);
// The same for the format of `output_path`.
// Commands ask before any work, so that such an image is not extracted for nothing.
void check_features_file_can_hold(const std::string& output_path, const std::string& image_path,
                                  const std::string& source_name);

}  // namespace aief::io

#include <filesystem>

#include "io/batch_output_names.hpp"
#include "io/feature_formats.hpp"
#include "io/option_record.hpp"
#include "io/temporary_files.hpp"
#include "tools/batch_sink.hpp"

namespace aief::cli {

namespace fs = std::filesystem;

namespace {

// OUTDIR/<name>.<format>, each written atomically (io::write_file_atomically).
class FilePerImageSink : public BatchSink {
 public:
  FilePerImageSink(const BatchSettings& settings, const io::FeatureFormat& format)
      : settings_(settings), format_(format) {
    std::error_code ec;
    fs::create_directories(settings.output_dir, ec);
    if (ec)
      throw Error("cannot create output folder '" + settings.output_dir + "': " + ec.message());
    // Killed writes' temporaries; those of another batch writing here now are locked and kept.
    io::remove_stale_temporaries(settings.output_dir);
  }

  Existing existing(const BatchInput& input, const io::SourceRecord& source) override {
    const std::string output = output_of(input);
    std::error_code ignored;
    fs::remove(io::temporary_path_of(output), ignored);  // a killed older aief's (shared names)
    fs::remove(output + ".tmp", ignored);                // ... of an aief before the short names
    Existing found;
    found.present = fs::exists(output, ignored);
    if (found.present) {
      const io::OutputRecord record = format_.record(output, source);
      found.of_this_input = record.of_source;
      if (found.of_this_input)
        found.option_changes = io::option_changes(record.options, settings_.options);
    }
    // Before the work: a name the format cannot hold (YAML: control characters).
    if (!found.current()) io::check_format_can_hold(format_, input.path, input.name);
    return found;
  }

  void write(const BatchInput& input, const Features& features,
             const io::SourceRecord& source) override {
    const std::string output = output_of(input);
    std::error_code ec;
    fs::create_directories(fs::path(output).parent_path(), ec);
    if (ec) {
      const std::string reason = "cannot create the folder of '" + output + "': " + ec.message();
      if (io::is_disk_failure(ec.value())) throw SinkFailure(reason);
      throw Error(reason);
    }
    try {
      format_.write(output, input.path, features, settings_.options, source);
    } catch (const io::WriteError& e) {
      if (e.of_the_disk()) throw SinkFailure(e.what());
      throw;
    }
  }

  std::string remove(const BatchInput& input) override {
    std::error_code ec;
    fs::remove(output_of(input), ec);
    return ec ? ec.message() : "";
  }

 private:
  std::string output_of(const BatchInput& input) const {
    return io::batch_output_path(settings_.output_dir, input.name, format_.name);
  }
  BatchSettings settings_;
  const io::FeatureFormat& format_;
};

}  // namespace

std::unique_ptr<BatchSink> make_file_per_image_sink(const BatchSettings& settings,
                                                    const io::FeatureFormat& format) {
  return std::make_unique<FilePerImageSink>(settings, format);
}

std::unique_ptr<BatchSink> make_batch_sink(const BatchSettings& settings) {
  const io::FeatureFormat* format = io::feature_format_named(settings.format);
  if (!format)
    throw Error("no features format '" + settings.format + "' (" + io::feature_format_names() +
                ")");
  return format->layout == io::FeatureFormat::Layout::file_per_image
             ? make_file_per_image_sink(settings, *format)
             : make_collection_sink(settings, *format);
}

}  // namespace aief::cli

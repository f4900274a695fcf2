// The sink of a one-file-per-batch format (io::FeatureCollectionFile: HDF5).
#include <mutex>
#include <string_view>
#include <unordered_set>

#include "aief/options.hpp"
#include "io/feature_formats.hpp"
#include "io/option_record.hpp"
#include "tools/batch_sink.hpp"

namespace aief::cli {

namespace {

// One file, an entry per input named by its name. Calls are serialised here: the pipeline asks
// from several threads, and a libhdf5 built without its thread-safe option allows one caller at a
// time.
class CollectionSink : public BatchSink {
 public:
  CollectionSink(const BatchSettings& settings, const io::FeatureFormat& format)
      : options_(settings.options),
        output_(settings.output_dir),
        file_(format.open(settings.output_dir)) {}

  Existing existing(const BatchInput& input, const io::SourceRecord& source) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    Existing found;
    found.of_this_input = file_->holds_from(input.name, source);
    found.present = found.of_this_input || file_->holds(input.name);
    if (found.of_this_input)
      found.option_changes = io::option_changes(file_->option_record(input.name), options_);
    return found;
  }

  void write(const BatchInput& input, const Features& features,
             const io::SourceRecord& source) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    file_->check_name(input.name);  // a name it cannot hold fails this input alone
    try {
      file_->write(input.name, features, source, options_);
    } catch (const Error& e) {
      throw SinkFailure(e.what());  // the file refuses every later write (io::Hdf5File)
    }
  }

  void finish() override {
    const std::lock_guard<std::mutex> lock(mutex_);
    try {
      file_->close();
    } catch (const Error& e) {
      throw SinkFailure(e.what());
    }
  }

  std::vector<std::string> entries_of_no_input(const std::vector<BatchInput>& inputs) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::unordered_set<std::string_view> taken;
    for (const BatchInput& input : inputs) taken.insert(input.name);
    std::vector<std::string> others;
    for (std::string& name : file_->names())
      if (!taken.count(name)) others.push_back(std::move(name));
    return others;
  }

  void refuse_mixed_descriptors(const std::vector<BatchInput>& inputs) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::unordered_set<std::string_view> taken;
    for (const BatchInput& input : inputs) taken.insert(input.name);
    for (const std::string& name : file_->names()) {
      if (taken.count(name)) continue;  // written again by this run, with its descriptor
      const DescriptorKind kept = io::recorded_descriptor(file_->option_record(name));
      if (kept == options_.descriptor) continue;
      throw Error("'" + output_ + "' holds " + std::string(to_string(kept)) +
                  " descriptors (image '" + name +
                  "', none of this run's images: another shard's, or gone from the folder) and "
                  "this run extracts " +
                  std::string(to_string(options_.descriptor)) +
                  " descriptors: one file would hold both, which never match each other (merge "
                  "refuses such files); write to another file, or extract with --descriptor " +
                  std::string(to_string(kept)) + "; nothing was written");
    }
  }

  int written_on_disk(int) const override {
    const std::lock_guard<std::mutex> lock(mutex_);
    return file_->writes_on_disk();
  }

  std::string remove(const BatchInput& input) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    try {
      file_->remove(input.name);
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }

 private:
  mutable std::mutex mutex_;
  ExtractorOptions options_;
  std::string output_;
  std::unique_ptr<io::FeatureCollectionFile> file_;
};

}  // namespace

std::unique_ptr<BatchSink> make_collection_sink(const BatchSettings& settings,
                                                const io::FeatureFormat& format) {
  if (!format.open) throw Error(format.missing);
  return std::make_unique<CollectionSink>(settings, format);
}

}  // namespace aief::cli

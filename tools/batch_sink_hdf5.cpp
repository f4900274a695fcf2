// The HDF5 sink, or, in a build without libhdf5, the refusal of --format h5.
#include <mutex>

#include "tools/batch_sink.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/option_record.hpp"
#endif

namespace aief::cli {

#ifdef AIEF_HAVE_HDF5

namespace {

// One hloc features file, a group per input named by its name (io/hdf5_file.hpp). Calls are
// serialised here: the pipeline asks from several threads, and a libhdf5 built without its
// thread-safe option allows one caller at a time.
class Hdf5Sink : public BatchSink {
 public:
  explicit Hdf5Sink(const BatchSettings& settings)
      : options_(settings.options), file_(settings.output_dir, io::Hdf5File::Mode::read_write) {}

  Existing existing(const BatchInput& input, const io::SourceRecord& source) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    Existing found;
    found.of_this_input = file_.features_belong_to(input.name, source);
    found.present = found.of_this_input || file_.has_features(input.name);
    if (found.of_this_input)
      found.option_changes = io::option_changes(file_.option_record(input.name), options_);
    return found;
  }

  void write(const BatchInput& input, const Features& features,
             const io::SourceRecord& source) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    try {
      file_.write_features(input.name, features, &source, &options_);
    } catch (const Error& e) {
      throw SinkFailure(e.what());  // the file refuses every later write (io::Hdf5File)
    }
  }

  void finish() override {
    const std::lock_guard<std::mutex> lock(mutex_);
    try {
      file_.close();
    } catch (const Error& e) {
      throw SinkFailure(e.what());
    }
  }

  std::string remove(const BatchInput& input) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    try {
      file_.remove_features(input.name);
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }

 private:
  std::mutex mutex_;
  ExtractorOptions options_;
  io::Hdf5File file_;
};

}  // namespace

std::unique_ptr<BatchSink> make_hdf5_sink(const BatchSettings& settings) {
  return std::make_unique<Hdf5Sink>(settings);
}

#else

std::unique_ptr<BatchSink> make_hdf5_sink(const BatchSettings&) {
  throw Error("this aief was built without HDF5 (install libhdf5-dev and rebuild)");
}

#endif

}  // namespace aief::cli

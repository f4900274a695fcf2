#include "tools/batch.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/batch_output_names.hpp"
#include "io/features_files.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_features.hpp"
#endif
#include "io/image_io.hpp"
#include "parallel/tsan_handoff.hpp"
#include "io/json_writer.hpp"
#include "tools/progress.hpp"

namespace aief::cli {

namespace fs = std::filesystem;

namespace {

// The pipeline's hand-offs, which TBB makes inside libtbb, unseen by ThreadSanitizer
// (parallel/tsan_handoff.hpp): each serial stage runs one call at a time, an item is listed
// before it is extracted and extracted before it is written. Globals: a stage must not read its
// closure before the acquire.
const char kListStage = 0, kExtractStage = 0, kWriteStage = 0;
struct HandoffOnExit {
  const char* tag;
  ~HandoffOnExit() { parallel::handoff_release(tag); }
};

// One image on its way through the pipeline.
struct Item {
  BatchInput input;
  std::size_t position = 0;  // in the batch's inputs
  std::string output;  // the file of a file-per-image format; empty for h5
  io::SourceRecord source;
  GrayImage image;
  Features features;
  std::string error;
  bool skip = false;       // its output is current
  bool replacing = false;  // an output was there, from another or a changed input
};

}  // namespace

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  auto number = [&](const std::string& digits, long long& value) {
    if (digits.empty() || digits.size() > 10 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
    value = std::stoll(digits);
    return value <= 2147483647LL;
  };
  long long index = -1, count = 0;
  if (slash == std::string::npos || !number(text.substr(0, slash), index) || !number(text.substr(slash + 1), count) ||
      count < 1)
    throw Error("--shard expects i/n, two integers with 0 <= i < n <= 2147483647, got '" + text + "'");
  if (index >= count)
    throw Error("--shard " + text + ": i counts from 0, so i < n (a 1-based Slurm array: --shard $((SLURM_ARRAY_TASK_ID - " +
                "SLURM_ARRAY_TASK_MIN))/$SLURM_ARRAY_TASK_COUNT)");
  return {static_cast<int>(index), static_cast<int>(count)};
}

std::vector<BatchInput> batch_inputs(const BatchSettings& settings) {
  const std::vector<BatchInput> all = io::list_batch_inputs(settings.input);
  io::check_batch_outputs_do_not_nest(all, settings.output_dir, settings.format);
  return io::shard_of(all, settings.shard_index, settings.shard_count);
}

bool batch_output_is_current(const std::string& output, const io::SourceRecord& source) {
  std::error_code ec;
  return fs::exists(output, ec) && io::features_file_belongs_to(output, source);
}

BatchSummary run_batch(const BatchSettings& settings) {
  const std::vector<BatchInput> inputs = batch_inputs(settings);
  std::error_code ec;
  // h5: every image a group of one file, named by the input's name, complete groups skipped on
  // resume; else a file per image (batch_output_path) holding its source record.
#ifdef AIEF_HAVE_HDF5
  std::unique_ptr<io::Hdf5File> h5;
  if (settings.format == "h5") h5 = std::make_unique<io::Hdf5File>(settings.output_dir, io::Hdf5File::Mode::read_write);
#else
  if (settings.format == "h5") throw Error("this aief was built without HDF5 (install libhdf5-dev and rebuild)");
  const void* h5 = nullptr;
#endif
  if (!h5) fs::create_directories(settings.output_dir, ec);
  if (ec) throw Error("cannot create output folder '" + settings.output_dir + "': " + ec.message());

  BatchSummary summary;
  summary.images = static_cast<int>(inputs.size());
  Progress progress("batch", summary.images);
  const int threads = settings.options.threads > 0 ? settings.options.threads : tbb::this_task_arena::max_concurrency();
  // Each worker thread keeps its own Extractor: buffers reused from image to image. Frames of
  // a batch are independent, so the extractor itself runs single-threaded.
  ExtractorOptions per_thread = settings.options;
  per_thread.threads = 1;
  tbb::enumerable_thread_specific<std::unique_ptr<Extractor>> extractors;

  // The pipeline's tokens are plain pointers to items owned here: TBB moves a token between
  // stages in its own inline code, which TSan does not instrument, so a token must not be an
  // object with its own synchronisation (a shared_ptr's count) or TSan sees the move as a race.
  // An item lives from the stage that lists it to the stage that writes it.
  std::vector<std::unique_ptr<Item>> items(inputs.size());
  // An output from another or older input must not stay beside a failure.
  const auto remove_output = [&](Item& item) {
#ifdef AIEF_HAVE_HDF5
    if (h5) {
      try {
        h5->remove_features(item.input.name);
      } catch (const std::exception& e) {
        item.error += std::string("; its old group could not be removed: ") + e.what();
      }
      return;
    }
#endif
    std::error_code ignored;
    fs::remove(item.output, ignored);
  };
  std::size_t next = 0;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        static_cast<std::size_t>(2 * threads),
        // Next image: serial, in order (the HDF5 file is asked here: one thread at a time).
        tbb::make_filter<void, Item*>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& control) -> Item* {
          parallel::handoff_acquire(&kListStage);
          const HandoffOnExit release_listed{&kListStage};
          if (next >= inputs.size()) {
            control.stop();
            return nullptr;
          }
          items[next] = std::make_unique<Item>();
          Item* item = items[next].get();
          item->position = next;
          item->input = inputs[next++];
#ifdef AIEF_HAVE_HDF5
          if (h5) {  // current: a complete group written from this very file (size and mtime)
            try {
              item->source = io::source_record_of(item->input.path, item->input.name);
              item->skip = h5->features_belong_to(item->input.name, item->source);
              item->replacing = !item->skip && h5->has_features(item->input.name);
            } catch (const std::exception& e) {
              item->error = e.what();
            }
            return item;
          }
#endif
          item->output = io::batch_output_path(settings.output_dir, item->input.name, settings.format);
          return item;
        }) &
            // Is the output current? If not: read (decoding dominates) and extract. Parallel.
            tbb::make_filter<Item*, Item*>(tbb::filter_mode::parallel, [&](Item* item) {
              parallel::handoff_acquire(&kListStage);
              const HandoffOnExit release_extracted{&kExtractStage};
              if (item->skip || !item->error.empty()) return item;
              try {
                if (!item->output.empty()) {  // a file per image (h5: asked by the listing stage)
                  item->source = io::source_record_of(item->input.path, item->input.name);
                  std::error_code ignored;
                  fs::remove(io::temporary_path_of(item->output), ignored);  // a killed run's
                  if (fs::exists(item->output, ignored)) {
                    item->skip = batch_output_is_current(item->output, item->source);
                    item->replacing = !item->skip;
                  }
                  // Before the work: a name the format cannot hold (YAML: control characters).
                  io::check_features_file_can_hold(item->output, item->input.path, item->input.name);
                }
                if (item->skip) return item;
                std::unique_ptr<Extractor>& extractor = extractors.local();
                if (!extractor) extractor = std::make_unique<Extractor>(per_thread);
                item->image = io::read_gray_image(item->input.path, settings.options.max_image_pixels, &item->source.warnings);
                extractor->extract(item->image.view(), item->features);
              } catch (const std::exception& e) {
                item->error = e.what();
              }
              item->image = GrayImage();
              return item;
            }) &
            // Write: serial (atomic rename), tally, progress.
            tbb::make_filter<Item*, void>(tbb::filter_mode::serial_out_of_order, [&](Item* item) {
              parallel::handoff_acquire(&kExtractStage);
              parallel::handoff_acquire(&kWriteStage);
              const HandoffOnExit release_written{&kWriteStage};
              for (const std::string& warning : item->source.warnings) std::cerr << "aief: warning: " << warning << "\n";
              if (item->skip) {
                ++summary.skipped;
              } else if (item->error.empty()) {
                try {
#ifdef AIEF_HAVE_HDF5
                  if (h5) {
                    h5->write_features(item->input.name, item->features, &item->source);
                  } else
#endif
                  {
                    fs::create_directories(fs::path(item->output).parent_path());
                    io::write_features(item->output, item->input.path, item->features, settings.options, item->source);
                  }
                  ++summary.extracted;
                  summary.replaced += item->replacing ? 1 : 0;
                  summary.keypoints += static_cast<long long>(item->features.keypoints.size());
                } catch (const std::exception& e) {
                  item->error = e.what();
                }
              }
              if (!item->error.empty()) {
                if (item->replacing) remove_output(*item);
                ++summary.failed;
                summary.failures.push_back(item->input.path + ": " + item->error);
              }
              progress.step(item->input.name);
              items[item->position].reset();
            }));
  });
  parallel::handoff_acquire(&kExtractStage);
  parallel::handoff_acquire(&kWriteStage);
  progress.finish();
  return summary;
}

}  // namespace aief::cli

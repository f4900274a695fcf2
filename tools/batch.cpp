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
#include "io/feature_formats.hpp"
#include "io/image_io.hpp"
#include "parallel/tsan_handoff.hpp"
#include "tools/batch_sink.hpp"
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
  io::SourceRecord source;
  Features features;
  std::string error;
  bool skip = false;                        // its output is current
  bool replacing = false;                   // an output was there, from another or a changed input
  std::vector<std::string> option_changes;  // an output of this input was there, of other options
};

// Stage 2, parallel: is the output current? If not: read (decoding dominates) and extract.
// With the carried F the images are frames of one video: one extractor sees every one of them in
// listing order (serial_in_order), a current output included, so F does not depend on which
// outputs a run found.
void extract_unless_current(Item& item, BatchSink& sink, const ExtractorOptions& options,
                            tbb::enumerable_thread_specific<std::unique_ptr<Extractor>>& extractors,
                            Extractor* video_extractor) {
  try {
    item.source = io::source_record_of(item.input.path, item.input.name);
    BatchSink::Existing existing = sink.existing(item.input, item.source);
    item.skip = existing.current();
    item.replacing = existing.present && !existing.of_this_input;
    item.option_changes = std::move(existing.option_changes);
    if (item.skip && !video_extractor) return;
    std::unique_ptr<Extractor>& extractor = extractors.local();
    if (!extractor && !video_extractor) {
      ExtractorOptions per_thread = options;  // frames are independent: one thread each
      per_thread.threads = 1;
      extractor = std::make_unique<Extractor>(per_thread);
    }
    const GrayImage image =
        io::read_gray_image(item.input.path, options.max_image_pixels, &item.source.warnings);
    (video_extractor ? *video_extractor : *extractor).extract(image.view(), item.features);
  } catch (const std::exception& e) {
    item.error = e.what();
  }
}

// An output of this input redone because its options differ: counted, and each change listed once.
void count_redone(const Item& item, BatchSummary& summary) {
  if (item.option_changes.empty()) return;
  ++summary.redone;
  for (const std::string& change : item.option_changes)
    if (std::find(summary.redone_for.begin(), summary.redone_for.end(), change) ==
        summary.redone_for.end())
      summary.redone_for.push_back(change);
}

// Stage 3, serial: write, or count the skip or the failure (an output of another or an older
// input, or of other options, must not stay beside a failure). A failure of the sink itself stops
// the batch.
void write_and_tally(Item& item, BatchSink& sink, BatchSummary& summary) {
  for (const std::string& warning : item.source.warnings)
    std::cerr << "aief: warning: " << warning << "\n";
  if (item.skip) {
    ++summary.skipped;
    return;
  }
  if (item.error.empty()) {
    try {
      sink.write(item.input, item.features, item.source);
      ++summary.extracted;
      summary.replaced += item.replacing ? 1 : 0;
      count_redone(item, summary);
      summary.keypoints += static_cast<long long>(item.features.keypoints.size());
      return;
    } catch (const SinkFailure& e) {
      summary.stopped = e.what();
      return;
    } catch (const std::exception& e) {
      item.error = e.what();
    }
  }
  if (item.replacing || !item.option_changes.empty()) {
    const std::string not_removed = sink.remove(item.input);
    if (!not_removed.empty()) item.error += "; its old output could not be removed: " + not_removed;
  }
  ++summary.failed;
  summary.failures.push_back(item.input.path + ": " + item.error);
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  auto number = [&](const std::string& digits, long long& value) {
    if (digits.empty() || digits.size() > 10 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    value = std::stoll(digits);
    return value <= 2147483647LL;
  };
  long long index = -1, count = 0;
  if (slash == std::string::npos || !number(text.substr(0, slash), index) ||
      !number(text.substr(slash + 1), count) || count < 1)
    throw Error("--shard expects i/n, two integers with 0 <= i < n <= 2147483647, got '" + text +
                "'");
  if (index >= count)
    throw Error(
        "--shard " + text +
        ": i counts from 0, so i < n (a 1-based Slurm array: --shard $((SLURM_ARRAY_TASK_ID - " +
        "SLURM_ARRAY_TASK_MIN))/$SLURM_ARRAY_TASK_COUNT)");
  return {static_cast<int>(index), static_cast<int>(count)};
}

std::vector<BatchInput> batch_inputs(const BatchSettings& settings) {
  // The frames of a video in frame order: each frame's carried F depends on the frames before.
  const bool frames = settings.options.carried_threshold;
  const std::vector<BatchInput> all = io::list_batch_inputs(
      settings.input, frames ? io::InputOrder::frames : io::InputOrder::by_name);
  if (frames)
    std::cerr << "aief: note: --entropy-threshold carried takes the frames of '" << settings.input
              << "' " << io::frame_order_of(settings.input) << "\n";
  io::check_batch_outputs_do_not_nest(all, settings.output_dir, settings.format);
  return io::shard_of(all, settings.shard_index, settings.shard_count);
}

BatchSummary run_batch(const BatchSettings& settings) {
  const std::vector<BatchInput> inputs = batch_inputs(settings);
  const std::unique_ptr<BatchSink> sink = make_batch_sink(settings);
  sink->refuse_mixed_descriptors(inputs);

  BatchSummary summary;
  summary.images = static_cast<int>(inputs.size());
  Progress progress("batch", summary.images);
  const int threads = settings.options.threads > 0 ? settings.options.threads
                                                   : tbb::this_task_arena::max_concurrency();
  // Each worker thread keeps its own Extractor: buffers reused from image to image.
  tbb::enumerable_thread_specific<std::unique_ptr<Extractor>> extractors;
  // The carried F: one extractor for the whole video, its frames in listing order.
  std::unique_ptr<Extractor> video_extractor;
  if (settings.options.carried_threshold) {
    video_extractor = std::make_unique<Extractor>(settings.options);
  }
  const tbb::filter_mode extract_mode =
      video_extractor ? tbb::filter_mode::serial_in_order : tbb::filter_mode::parallel;

  // The pipeline's tokens are plain pointers to items owned here: TBB moves a token between
  // stages in its own inline code, which TSan does not instrument, so a token must not be an
  // object with its own synchronisation (a shared_ptr's count) or TSan sees the move as a race.
  // An item lives from the stage that lists it to the stage that writes it.
  std::vector<std::unique_ptr<Item>> items(inputs.size());
  std::size_t next = 0;
  std::atomic<bool> stop{false};  // the sink failed: list no more
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        static_cast<std::size_t>(2 * threads),
        tbb::make_filter<void, Item*>(tbb::filter_mode::serial_in_order,
                                      [&](tbb::flow_control& control) -> Item* {
                                        parallel::handoff_acquire(&kListStage);
                                        const HandoffOnExit release_listed{&kListStage};
                                        if (next >= inputs.size() || stop.load()) {
                                          control.stop();
                                          return nullptr;
                                        }
                                        items[next] = std::make_unique<Item>();
                                        Item* item = items[next].get();
                                        item->position = next;
                                        item->input = inputs[next++];
                                        return item;
                                      }) &
            tbb::make_filter<Item*, Item*>(extract_mode,
                                           [&](Item* item) {
                                             parallel::handoff_acquire(&kListStage);
                                             const HandoffOnExit release_extracted{&kExtractStage};
                                             if (!stop.load())
                                               extract_unless_current(*item, *sink,
                                                                      settings.options, extractors,
                                                                      video_extractor.get());
                                             return item;
                                           }) &
            tbb::make_filter<Item*, void>(tbb::filter_mode::serial_out_of_order, [&](Item* item) {
              parallel::handoff_acquire(&kExtractStage);
              parallel::handoff_acquire(&kWriteStage);
              const HandoffOnExit release_written{&kWriteStage};
              if (summary.stopped.empty()) {
                write_and_tally(*item, *sink, summary);
                if (!summary.stopped.empty()) stop.store(true);
                progress.step(item->input.name);
              }
              items[item->position].reset();
            }));
  });
  // Every stage's last call happens before this line (its final call of the list stage is the
  // one that stops the pipeline, followed by no extraction): joined here for TSan.
  parallel::handoff_acquire(&kListStage);
  parallel::handoff_acquire(&kExtractStage);
  parallel::handoff_acquire(&kWriteStage);
  if (summary.stopped.empty()) {
    try {
      summary.of_no_input = sink->entries_of_no_input(inputs);
    } catch (const std::exception&) {  // a note only: the batch itself is done
    }
    try {
      sink->finish();
    } catch (const SinkFailure& e) {
      summary.stopped = e.what();
    }
  }
  summary.on_disk = sink->written_on_disk(summary.extracted);
  progress.finish();
  return summary;
}

}  // namespace aief::cli

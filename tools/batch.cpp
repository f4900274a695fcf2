#include "tools/batch.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/features_files.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_features.hpp"
#endif
#include "io/image_io.hpp"
#include "tools/progress.hpp"

namespace aief::cli {

namespace fs = std::filesystem;

namespace {

bool is_image_name(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const char* const kExtensions[] = {".png", ".jpg", ".jpeg", ".pgm", ".ppm", ".pbm", ".bmp", ".tif", ".tiff", ".webp"};
  return std::any_of(std::begin(kExtensions), std::end(kExtensions), [&](const char* e) { return ext == e; });
}

// One image on its way through the pipeline.
struct Item {
  std::string input, output;
  std::string name;  // for h5
  GrayImage image;
  Features features;
  std::string error;
  bool skip = false;
};

}  // namespace

std::vector<std::string> batch_inputs(const BatchSettings& settings) {
  std::vector<std::string> all;
  std::error_code ec;
  if (fs::is_directory(settings.input, ec)) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(settings.input, ec))
      if (entry.is_regular_file() && is_image_name(entry.path())) all.push_back(entry.path().string());
    if (ec) throw Error("cannot list '" + settings.input + "': " + ec.message());
  } else {
    std::ifstream list(settings.input);
    if (!list) throw Error("batch input '" + settings.input + "' is neither a folder nor a readable list file");
    for (std::string line; std::getline(list, line);) {
      line.erase(line.find_last_not_of(" \t\r") + 1);
      if (!line.empty() && line[0] != '#') all.push_back(line);
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  std::vector<std::string> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(settings.shard_count)) == settings.shard_index) mine.push_back(all[i]);
  return mine;
}

std::string batch_output_path(const BatchSettings& settings, const std::string& input) {
  std::error_code ec;
  fs::path relative = fs::is_directory(settings.input, ec) ? fs::relative(input, settings.input, ec) : fs::path(input);
  if (ec || relative.empty()) relative = fs::path(input).filename();
  std::string name = relative.replace_extension().generic_string();
  std::size_t at = 0;
  while ((at = name.find('/', at)) != std::string::npos) name.replace(at, 1, "__");
  while (!name.empty() && (name[0] == '.' || name[0] == '_')) name.erase(0, 1);  // "../x" stays inside OUTDIR
  return (fs::path(settings.output_dir) / (name + "." + settings.format)).string();
}

std::string batch_image_name(const BatchSettings& settings, const std::string& input) {
  std::error_code ec;
  fs::path relative = fs::is_directory(settings.input, ec) ? fs::relative(input, settings.input, ec) : fs::path(input);
  if (ec || relative.empty()) relative = fs::path(input).filename();
  return relative.lexically_normal().generic_string();
}

BatchSummary run_batch(const BatchSettings& settings) {
  const std::vector<std::string> inputs = batch_inputs(settings);
  std::error_code ec;
  // h5: every image a group of one file, complete groups skipped on resume; else a file per image.
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

  std::size_t next = 0;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        static_cast<std::size_t>(2 * threads),
        // Next image: serial, in order; an image whose output is complete is skipped.
        tbb::make_filter<void, std::shared_ptr<Item>>(tbb::filter_mode::serial_in_order,
                                                       [&](tbb::flow_control& control) -> std::shared_ptr<Item> {
                                                         if (next >= inputs.size()) {
                                                           control.stop();
                                                           return nullptr;
                                                         }
                                                         auto item = std::make_shared<Item>();
                                                         item->input = inputs[next++];
                                                         item->output = batch_output_path(settings, item->input);
                                                         item->name = batch_image_name(settings, item->input);
#ifdef AIEF_HAVE_HDF5
                                                         item->skip = h5 ? h5->has_features(item->name) : fs::exists(item->output);
#else
                                                         item->skip = fs::exists(item->output);
#endif
                                                         return item;
                                                       }) &
            // Read (decoding dominates) and extract: parallel.
            tbb::make_filter<std::shared_ptr<Item>, std::shared_ptr<Item>>(tbb::filter_mode::parallel,
                                                                          [&](std::shared_ptr<Item> item) {
                                                                            if (item->skip) return item;
                                                                            std::unique_ptr<Extractor>& extractor = extractors.local();
                                                                            if (!extractor) extractor = std::make_unique<Extractor>(per_thread);
                                                                            try {
                                                                              item->image = io::read_gray_image(item->input);
                                                                              extractor->extract(item->image.view(), item->features);
                                                                            } catch (const std::exception& e) {
                                                                              item->error = e.what();
                                                                            }
                                                                            item->image = GrayImage();
                                                                            return item;
                                                                          }) &
            // Write: serial (atomic rename), tally, progress.
            tbb::make_filter<std::shared_ptr<Item>, void>(tbb::filter_mode::serial_out_of_order, [&](std::shared_ptr<Item> item) {
              if (item->skip) {
                ++summary.skipped;
              } else if (item->error.empty()) {
                try {
#ifdef AIEF_HAVE_HDF5
                  if (h5)
                    h5->write_features(item->name, item->features);
                  else
#endif
                    io::write_features(item->output, item->input, item->features, settings.options);
                  ++summary.extracted;
                  summary.keypoints += static_cast<long long>(item->features.keypoints.size());
                } catch (const std::exception& e) {
                  item->error = e.what();
                }
              }
              if (!item->error.empty()) {
                ++summary.failed;
                summary.failures.push_back(item->input + ": " + item->error);
              }
              progress.step(h5 ? item->name : fs::path(item->output).filename().string());
            }));
  });
  progress.finish();
  return summary;
}

}  // namespace aief::cli

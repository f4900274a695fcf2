#include "io/feature_formats.hpp"

#include <cctype>
#include <filesystem>

#include "aief/error.hpp"
#include "io/features_files.hpp"
#include "io/npz_writer.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif

namespace aief::io {

namespace {

using Layout = FeatureFormat::Layout;

void write_npz(const std::string& path, const std::string&, const Features& features,
               const ExtractorOptions& options, const std::optional<SourceRecord>& source) {
  write_features_npz(path, features, options, source);
}

#ifdef AIEF_HAVE_HDF5
// hloc's features.h5, a group per image.
class Hdf5Collection : public FeatureCollectionFile {
 public:
  // Refuses a file it must not add to: a matches file, or another tool's features (hloc's
  // SuperPoint: 256 x N float32 descriptors), whose groups a resume would replace.
  explicit Hdf5Collection(const std::string& path) : file_(path, Hdf5File::Mode::read_write) {
    if (file_.holds_pairs())
      throw Error("'" + path +
                  "' holds matches (pair groups with matches0): write features to a file of "
                  "their own; nothing was written");
    if (const std::string& image = file_.first_image_group(); !image.empty())
      if (const std::string other = file_.foreign_descriptors(image); !other.empty())
        throw Error("'" + path + "' holds another tool's features (image '" + image +
                    "': " + other +
                    " descriptors; aief writes 32 x N uint8): write aief's features to a file of "
                    "their own; nothing was written");
  }
  bool holds(const std::string& name) const override { return file_.has_features(name); }
  bool holds_from(const std::string& name, const SourceRecord& source) const override {
    return file_.features_belong_to(name, source);
  }
  std::optional<std::string> option_record(const std::string& name) const override {
    return file_.option_record(name);
  }
  void write(const std::string& name, const Features& features, const SourceRecord& source,
             const ExtractorOptions& options) override {
    file_.write_features(name, features, &source, &options);
  }
  void remove(const std::string& name) override { file_.remove_features(name); }
  void close() override { file_.close(); }

 private:
  Hdf5File file_;
};

std::unique_ptr<FeatureCollectionFile> open_hdf5(const std::string& path) {
  return std::make_unique<Hdf5Collection>(path);
}
#else
constexpr std::unique_ptr<FeatureCollectionFile> (*open_hdf5)(const std::string&) = nullptr;
#endif

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// "a, b or c"
std::string or_list(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return text;
}

}  // namespace

const std::vector<FeatureFormat>& feature_formats() {
  static const std::vector<FeatureFormat> formats = {
      {"json",
       "JSON",
       {".json"},
       Layout::file_per_image,
       &write_features_json,
       &json_file_record,
       nullptr,
       nullptr,
       nullptr},
      {"yml",
       "OpenCV FileStorage YAML",
       {".yml", ".yaml"},
       Layout::file_per_image,
       &write_features_yaml,
       &yaml_file_record,
       &check_yaml_can_hold,
       nullptr,
       nullptr},
      {"npz",
       "numpy",
       {".npz"},
       Layout::file_per_image,
       &write_npz,
       &npz_file_record,
       nullptr,
       nullptr,
       nullptr},
      {"h5",
       "HDF5 in hloc's layout",
       {".h5"},
       Layout::one_file_per_batch,
       nullptr,
       nullptr,
       nullptr,
       open_hdf5,
       "this aief was built without HDF5 (install libhdf5-dev and rebuild)"},
  };
  return formats;
}

const FeatureFormat* feature_format_named(const std::string& name) {
  for (const FeatureFormat& format : feature_formats())
    if (name == format.name) return &format;
  return nullptr;
}

const FeatureFormat* feature_format_of_path(const std::string& path) {
  const std::string ext = extension_of(path);
  for (const FeatureFormat& format : feature_formats())
    for (const char* extension : format.extensions)
      if (ext == extension) return &format;
  return nullptr;
}

std::string feature_format_names() {
  std::vector<std::string> names;
  for (const FeatureFormat& format : feature_formats()) names.push_back(format.name);
  return or_list(names);
}

std::vector<const FeatureFormat*> feature_formats_of(FeatureFormat::Layout layout) {
  std::vector<const FeatureFormat*> formats;
  for (const FeatureFormat& format : feature_formats())
    if (format.layout == layout) formats.push_back(&format);
  return formats;
}

std::string feature_format_extensions(FeatureFormat::Layout layout) {
  std::vector<std::string> extensions;
  for (const FeatureFormat& format : feature_formats())
    if (format.layout == layout)
      for (const char* extension : format.extensions) extensions.push_back(extension);
  return or_list(extensions);
}

namespace {

// The file-per-image format of `path`, or nullptr.
const FeatureFormat* file_per_image_format_of(const std::string& path) {
  const FeatureFormat* format = feature_format_of_path(path);
  return format && format->layout == Layout::file_per_image ? format : nullptr;
}

}  // namespace

void write_features(const std::string& path, const std::string& image_path,
                    const Features& features, const ExtractorOptions& options,
                    const std::optional<SourceRecord>& source) {
  const FeatureFormat* format = file_per_image_format_of(path);
  if (!format)
    throw Error("output '" + path + "' must end in " +
                feature_format_extensions(Layout::file_per_image));
  check_format_can_hold(*format, image_path, source ? source->name : image_path);
  format->write(path, image_path, features, options, source);
}

OutputRecord features_file_record(const std::string& output_path, const SourceRecord& source) {
  const FeatureFormat* format = file_per_image_format_of(output_path);
  return format ? format->record(output_path, source) : OutputRecord{};
}

bool features_file_belongs_to(const std::string& output_path, const SourceRecord& source) {
  return features_file_record(output_path, source).of_source;
}

bool is_features_file_name(const std::string& path) {
  return file_per_image_format_of(path) != nullptr;
}

void check_format_can_hold(const FeatureFormat& format, const std::string& image_path,
                           const std::string& source_name) {
  if (!format.check_can_hold) return;
  try {
    format.check_can_hold(image_path, source_name);
  } catch (const Error& e) {
    std::vector<std::string> holding_any;  // the first extension of each format that holds any name
    for (const FeatureFormat* other : feature_formats_of(format.layout))
      if (!other->check_can_hold) holding_any.push_back(other->extensions.front());
    throw Error(std::string(e.what()) + " (write " + or_list(holding_any) + " for such names)");
  }
}

void check_features_file_can_hold(const std::string& output_path, const std::string& image_path,
                                  const std::string& source_name) {
  if (const FeatureFormat* format = file_per_image_format_of(output_path))
    check_format_can_hold(*format, image_path, source_name);
}

}  // namespace aief::io

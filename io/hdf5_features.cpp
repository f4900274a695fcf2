// Hdf5File's image groups (the features.h5 layout, io/hdf5_file.hpp).
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "aief/error.hpp"
#include "io/hdf5_file.hpp"
#include "io/hdf5_guarded_write.hpp"
#include "io/hdf5_objects.hpp"
#include "io/option_record.hpp"

namespace aief::io {

using namespace hdf5;

std::string image_group(const std::string& image) {
  if (!image.empty() && image[0] == '/') return std::string("%2F").append(image);
  if (!image.empty() && image[0] == '%') return std::string("%25").append(image, 1);
  return image;
}

std::string image_of_group(const std::string& group) {
  if (group.rfind("%2F/", 0) == 0) return group.substr(3);
  // Appended, not "%" + ...: GCC 12 warns falsely (-Wrestrict) on the sum.
  if (group.rfind("%25", 0) == 0) return std::string("%").append(group, 3);
  return group;
}

bool Hdf5File::has_features(const std::string& image) const {
  const std::string name = image_group(image);
  return may_hold(name) && exists(file_, name + "/image_size");
}
bool Hdf5File::features_belong_to(const std::string& image, const SourceRecord& source) const {
  const std::optional<SourceRecord> stored = recorded_source(image);
  return stored && stored->bytes == source.bytes && stored->mtime_ns == source.mtime_ns;
}

std::optional<SourceRecord> Hdf5File::recorded_source(const std::string& image) const {
  const std::string name = image_group(image);
  if (!has_features(image) || !exists(file_, name + "/source")) return std::nullopt;
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  std::vector<hsize_t> dims;
  const std::vector<std::int64_t> stored =
      read_dataset<std::int64_t>(group.get(), "source", dims, name);
  if (stored.size() != 2) return std::nullopt;
  return SourceRecord{image, static_cast<std::uintmax_t>(stored[0]), stored[1], {}};
}

std::optional<std::string> Hdf5File::option_record(const std::string& image) const {
  const std::string name = image_group(image);
  silence_hdf5();
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) return std::nullopt;
  std::string record = string_attribute(group.get(), "options");
  if (record.empty()) return std::nullopt;
  return record;
}

void Hdf5File::remove_features(const std::string& image) {
  const std::string name = image_group(image);
  // Flushed at once: a file created by an older aief hands freed space out again.
  write_guarded(
      0, "the removal of '" + name + "'", [&] { remove_group(file_, name); }, Flush::now, false);
}

void Hdf5File::check_image_name(const std::string& image) const {
  const std::string group = image_group(image);
  if (image.empty())
    throw Error("cannot write an image named '' to '" + path_ + "': an image needs a name");
  // libhdf5 reads a last part '.' ("."; "x/."; "x/./") as the group it is in, which exists:
  // the write would fail half done, so it is refused before anything is written.
  const std::string_view trimmed(group.data(), group.find_last_not_of('/') + 1);
  if (trimmed == "." || (trimmed.size() >= 2 && trimmed.substr(trimmed.size() - 2) == "/."))
    throw Error("cannot write an image named '" + image + "' to '" + path_ +
                "': HDF5 reads a name ending in '.' as the group that holds it, not a group of "
                "its own; nothing was written for it");
  // The groups on its path: none may be an image's.
  for (std::size_t at = group.find('/', 1); at != std::string::npos; at = group.find('/', at + 1)) {
    const std::string folder = group.substr(0, at);
    if (may_hold(folder) && exists(file_, folder + "/image_size"))
      throw Error("cannot write image '" + image + "' to '" + path_ +
                  "': its group would go inside the group of image '" + image_of_group(folder) +
                  "' (one image's name is the folder of another's); nothing was written for it");
  }
  // Its own group, when there, must be an image's, not a folder of other images' groups.
  if (may_hold(group) && exists(file_, group) && !exists(file_, group + "/image_size")) {
    const Handle folder(H5Gopen2(file_, group.c_str(), H5P_DEFAULT), H5Gclose);
    H5G_info_t info{};
    if (folder.ok() && H5Gget_info(folder.get(), &info) >= 0 && info.nlinks > 0 &&
        !exists(file_, group + "/keypoints"))
      throw Error("cannot write image '" + image + "' to '" + path_ +
                  "': its group is the folder of other images' groups (such as '" + image +
                  "/...'), which it would replace; nothing was written for it");
  }
}

void Hdf5File::write_features(const std::string& image, const Features& features,
                              const SourceRecord* source, const ExtractorOptions* options) {
  silence_hdf5();
  const std::string name = image_group(image);
  check_image_name(image);
  // A group being replaced goes first, flushed, so that no new data lands in its space while the
  // file on disk still holds it.
  if (may_hold(name) && exists(file_, name)) remove_features(image);
  const std::size_t n = features.keypoints.size();
  std::vector<float> xy(2 * n), size(n), angle(n), response(n);
  std::vector<std::int32_t> octave(n);
  std::vector<std::uint8_t> descriptors(kDescriptorBytes * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Keypoint& kp = features.keypoints[i];
    xy[2 * i] = kp.x;
    xy[2 * i + 1] = kp.y;
    size[i] = kp.size;
    angle[i] = kp.angle_deg;
    response[i] = kp.response;
    octave[i] = kp.octave;
    for (std::size_t b = 0; b < kDescriptorBytes; ++b)
      descriptors[b * n + i] = features.descriptors[i][b];  // 32 x N
  }
  const hsize_t count = n;
  const std::uint64_t bytes =
      n * (2 * sizeof(float) + kDescriptorBytes + 3 * sizeof(float) + sizeof(std::int32_t));
  write_guarded(bytes, "image '" + name + "'", [&] {
    const Handle group = create_group(file_, name, path_);
    note_group(name);
    write_dataset(group.get(), "keypoints", {count, 2}, xy, name);
    write_dataset(group.get(), "descriptors", {kDescriptorBytes, count}, descriptors, name);
    write_dataset(group.get(), "scores", {count}, response, name);
    write_dataset(group.get(), "size", {count}, size, name);
    write_dataset(group.get(), "angle", {count}, angle, name);
    write_dataset(group.get(), "octave", {count}, octave, name);
    if (source)
      write_dataset(
          group.get(), "source", {2},
          std::vector<std::int64_t>{static_cast<std::int64_t>(source->bytes), source->mtime_ns},
          name);
    if (options) write_string_attribute(group.get(), "options", option_record_json(*options));
    // Last: its presence marks the group complete (has_features).
    write_dataset(group.get(), "image_size", {2},
                  std::vector<std::int64_t>{features.image_width, features.image_height}, name);
  });
}

std::vector<Descriptor> Hdf5File::read_descriptors(const std::string& image) const {
  const std::string name = image_group(image);
  if (!exists(file_, name + "/descriptors"))
    throw Error("no image '" + name + "' in '" + path_ + "'");
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  std::vector<hsize_t> dims;
  const std::vector<std::uint8_t> bytes =
      read_dataset<std::uint8_t>(group.get(), "descriptors", dims, name);
  if (dims.size() != 2 || dims[0] != kDescriptorBytes)
    throw Error("'" + name + "/descriptors' in '" + path_ +
                "' is not 32 x N (aief's binary descriptors)");
  const std::size_t n = dims[1];
  std::vector<Descriptor> descriptors(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < kDescriptorBytes; ++b) descriptors[i][b] = bytes[b * n + i];
  return descriptors;
}

std::string Hdf5File::foreign_descriptors(const std::string& group) const {
  silence_hdf5();
  const Handle set(H5Dopen2(file_, (group + "/descriptors").c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.ok()) return "no descriptors";
  const Handle space(H5Dget_space(set.get()), H5Sclose);
  const Handle type(H5Dget_type(set.get()), H5Tclose);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank == 2) H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  const bool bytes = H5Tget_class(type.get()) == H5T_INTEGER && H5Tget_size(type.get()) == 1;
  if (rank == 2 && dims[0] == kDescriptorBytes && bytes) return "";
  const H5T_class_t kind = H5Tget_class(type.get());
  // numpy's names: uint8 for unsigned bytes (SuperPoint's float32, aief's uint8), int8 signed.
  const bool is_unsigned = kind == H5T_INTEGER && H5Tget_sign(type.get()) == H5T_SGN_NONE;
  const std::string type_name = (kind == H5T_FLOAT     ? "float"
                                 : is_unsigned         ? "uint"
                                 : kind == H5T_INTEGER ? "int"
                                                       : "other") +
                                std::to_string(8 * H5Tget_size(type.get()));
  if (rank != 2) return "descriptors of rank " + std::to_string(rank) + ", " + type_name;
  return std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " " + type_name;
}

Features Hdf5File::read_features(const std::string& image) const {
  const std::string name = image_group(image);
  if (!exists(file_, name)) throw Error("no image '" + name + "' in '" + path_ + "'");
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) throw Error("'" + name + "' in '" + path_ + "' is not a group");
  std::vector<hsize_t> dims;
  const std::vector<float> xy = read_dataset<float>(group.get(), "keypoints", dims, name);
  if (dims.size() != 2 || dims[1] != 2)
    throw Error("'" + name + "/keypoints' in '" + path_ + "' is not N x 2");
  const std::size_t n = dims[0];
  const std::vector<std::uint8_t> descriptors =
      read_dataset<std::uint8_t>(group.get(), "descriptors", dims, name);
  if (dims.size() != 2 || dims[0] != kDescriptorBytes || dims[1] != n)
    throw Error("'" + name + "/descriptors' in '" + path_ + "' is not 32 x " + std::to_string(n) +
                " (aief's binary descriptors)");
  // Each read in the type it is stored as: a conversion would cost libhdf5 a 1 MB buffer cleared
  // per read (about 1 M instructions, more than the rest of the image).
  const auto optional = [&](const char* dataset, auto zero) {
    std::vector<hsize_t> d;
    using T = decltype(zero);
    return exists(group.get(), dataset) ? read_dataset<T>(group.get(), dataset, d, name)
                                        : std::vector<T>(n, zero);
  };
  const std::vector<float> scores = optional("scores", 0.0f), size = optional("size", 0.0f),
                           angle = optional("angle", 0.0f);
  const std::vector<std::int32_t> octave = optional("octave", std::int32_t{0});
  const std::vector<std::int64_t> image_size =
      read_dataset<std::int64_t>(group.get(), "image_size", dims, name);
  Features features;
  features.descriptor = recorded_descriptor(option_record(image));
  if (image_size.size() == 2) {
    features.image_width = static_cast<int>(image_size[0]);
    features.image_height = static_cast<int>(image_size[1]);
  }
  features.keypoints.resize(n);
  features.descriptors.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Keypoint& kp = features.keypoints[i];
    kp.x = xy[2 * i];
    kp.y = xy[2 * i + 1];
    kp.size = i < size.size() ? size[i] : 0;
    kp.angle_deg = i < angle.size() ? angle[i] : 0;
    kp.response = i < scores.size() ? scores[i] : 0;
    kp.octave = i < octave.size() ? static_cast<int>(octave[i]) : 0;
    for (std::size_t b = 0; b < kDescriptorBytes; ++b)
      features.descriptors[i][b] = descriptors[b * n + i];
  }
  return features;
}
std::vector<std::string> Hdf5File::feature_names() const { return listing().names; }

Hdf5File::Listing Hdf5File::listing() const {
  silence_hdf5();
  struct Visit {
    Listing listing;
    std::vector<std::string> with_keypoints;
  } visited;
  const auto visit = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
    if (info->type != H5O_TYPE_DATASET) return 0;
    Visit& v = *static_cast<Visit*>(data);
    const std::string_view path(name);
    const auto group_of = [&](std::string_view suffix) -> std::optional<std::string> {
      if (path.size() <= suffix.size() || !path.ends_with(suffix)) return std::nullopt;
      return image_of_group(std::string(path.substr(0, path.size() - suffix.size())));
    };
    if (auto image = group_of("/image_size"))
      v.listing.names.push_back(std::move(*image));
    else if (auto started = group_of("/keypoints"))
      v.with_keypoints.push_back(std::move(*started));
    else if (path.ends_with("/matches0"))
      v.listing.holds_pairs = true;
    return 0;
  };
  // Only each object's type (H5O_INFO_BASIC): the full information reads every header's
  // attributes and sizes too, 340k instructions an image.
  if (H5Ovisit2(file_, H5_INDEX_NAME, H5_ITER_INC, visit, &visited, H5O_INFO_BASIC) < 0)
    throw Error(damaged_file(path_, hdf5_reason()));
  Listing& out = visited.listing;
  std::sort(out.names.begin(), out.names.end());
  for (std::string& name : visited.with_keypoints)
    if (!std::binary_search(out.names.begin(), out.names.end(), name))
      out.incomplete.push_back(std::move(name));
  std::sort(out.incomplete.begin(), out.incomplete.end());
  return out;
}
}  // namespace aief::io

#include "io/hdf5_features.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include <hdf5.h>

#include "aief/error.hpp"

namespace aief::io {

namespace {

// One HDF5 handle, closed by its own close function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// Errors are reported by aief::Error; libhdf5's own stack printing would only repeat them.
void silence_hdf5() {
  static const bool silenced = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)silenced;
}

// Whether every component of `path` exists (H5Lexists fails when a parent is missing).
bool exists(hid_t file, const std::string& path) {
  std::size_t at = 0;
  while (true) {
    at = path.find('/', at + 1);
    const std::string prefix = path.substr(0, at);
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (at == std::string::npos) return true;
  }
}

template <class T>
hid_t native_type();
template <>
hid_t native_type<float>() { return H5T_NATIVE_FLOAT; }
template <>
hid_t native_type<std::uint8_t>() { return H5T_NATIVE_UINT8; }
template <>
hid_t native_type<std::int32_t>() { return H5T_NATIVE_INT32; }
template <>
hid_t native_type<std::int64_t>() { return H5T_NATIVE_INT64; }

template <class T>
void write_dataset(hid_t group, const char* name, const std::vector<hsize_t>& dims, const std::vector<T>& values,
                   const std::string& where) {
  const Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  const Handle set(H5Dcreate2(group, name, native_type<T>(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!set.ok()) throw Error("cannot create dataset '" + where + "/" + name + "'");
  if (!values.empty() && H5Dwrite(set.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw Error("cannot write dataset '" + where + "/" + name + "' (disk full?)");
}

// The dataset's dimensions and values, converted to T by libhdf5.
template <class T>
std::vector<T> read_dataset(hid_t group, const char* name, std::vector<hsize_t>& dims, const std::string& where) {
  const Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  if (!set.ok()) throw Error("no dataset '" + where + "/" + name + "'");
  const Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  dims.assign(static_cast<std::size_t>(std::max(rank, 0)), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  std::vector<T> values(static_cast<std::size_t>(count));
  if (count > 0 && H5Dread(set.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw Error("cannot read dataset '" + where + "/" + name + "'");
  return values;
}

Handle create_group(hid_t file, const std::string& name, const std::string& path) {
  const Handle intermediate(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(intermediate.get(), 1);
  Handle group(H5Gcreate2(file, name.c_str(), intermediate.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!group.ok()) throw Error("cannot create group '" + name + "' in '" + path + "'");
  return group;
}

// Removes a group: one a killed run left without its last dataset, or one being replaced.
void remove_group(hid_t file, const std::string& name) {
  if (exists(file, name)) H5Ldelete(file, name.c_str(), H5P_DEFAULT);
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path, Mode mode) : path_(path) {
  silence_hdf5();
  std::error_code ec;
  if (mode == Mode::read) {
    if (!std::filesystem::exists(path, ec)) throw Error("cannot open '" + path + "': no such file");
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  } else if (std::filesystem::exists(path, ec)) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  } else {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT);
  }
  if (file_ < 0) throw Error("cannot open '" + path + "' as an HDF5 file (damaged, or not HDF5?)");
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) H5Fclose(file_);
}

bool Hdf5File::has_features(const std::string& name) const { return exists(file_, name + "/image_size"); }

bool Hdf5File::has_matches(const std::string& pair_name) const { return exists(file_, pair_name + "/matching_scores0"); }

bool Hdf5File::features_belong_to(const std::string& name, const SourceRecord& source) const {
  if (!has_features(name) || !exists(file_, name + "/source")) return false;
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  std::vector<hsize_t> dims;
  const std::vector<std::int64_t> stored = read_dataset<std::int64_t>(group.get(), "source", dims, name);
  return stored.size() == 2 && static_cast<std::uintmax_t>(stored[0]) == source.bytes && stored[1] == source.mtime_ns;
}

void Hdf5File::remove_features(const std::string& name) {
  remove_group(file_, name);
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) throw Error("cannot flush '" + path_ + "' (disk full?)");
}

void Hdf5File::write_features(const std::string& name, const Features& features, const SourceRecord* source) {
  remove_group(file_, name);
  const Handle group = create_group(file_, name, path_);
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
    for (std::size_t b = 0; b < kDescriptorBytes; ++b) descriptors[b * n + i] = features.descriptors[i][b];  // 32 x N
  }
  const hsize_t count = n;
  write_dataset(group.get(), "keypoints", {count, 2}, xy, name);
  write_dataset(group.get(), "descriptors", {kDescriptorBytes, count}, descriptors, name);
  write_dataset(group.get(), "scores", {count}, response, name);
  write_dataset(group.get(), "size", {count}, size, name);
  write_dataset(group.get(), "angle", {count}, angle, name);
  write_dataset(group.get(), "octave", {count}, octave, name);
  if (source)
    write_dataset(group.get(), "source", {2},
                  std::vector<std::int64_t>{static_cast<std::int64_t>(source->bytes), source->mtime_ns}, name);
  // Last: its presence marks the group complete (has_features).
  write_dataset(group.get(), "image_size", {2}, std::vector<std::int64_t>{features.image_width, features.image_height}, name);
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) throw Error("cannot flush '" + path_ + "' (disk full?)");
}

Features Hdf5File::read_features(const std::string& name) const {
  if (!exists(file_, name)) throw Error("no image '" + name + "' in '" + path_ + "'");
  const Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) throw Error("'" + name + "' in '" + path_ + "' is not a group");
  std::vector<hsize_t> dims;
  const std::vector<float> xy = read_dataset<float>(group.get(), "keypoints", dims, name);
  if (dims.size() != 2 || dims[1] != 2) throw Error("'" + name + "/keypoints' in '" + path_ + "' is not N x 2");
  const std::size_t n = dims[0];
  const std::vector<std::uint8_t> descriptors = read_dataset<std::uint8_t>(group.get(), "descriptors", dims, name);
  if (dims.size() != 2 || dims[0] != kDescriptorBytes || dims[1] != n)
    throw Error("'" + name + "/descriptors' in '" + path_ + "' is not 32 x " + std::to_string(n) + " (aief's binary descriptors)");
  const auto optional = [&](const char* dataset) {
    std::vector<hsize_t> d;
    return exists(group.get(), dataset) ? read_dataset<float>(group.get(), dataset, d, name) : std::vector<float>(n, 0.0f);
  };
  const std::vector<float> scores = optional("scores"), size = optional("size"), angle = optional("angle"),
                           octave = optional("octave");
  const std::vector<std::int64_t> image_size = read_dataset<std::int64_t>(group.get(), "image_size", dims, name);
  Features features;
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
    for (std::size_t b = 0; b < kDescriptorBytes; ++b) features.descriptors[i][b] = descriptors[b * n + i];
  }
  return features;
}

void Hdf5File::write_matches(const std::string& pair_name, int keypoints0, const std::vector<Match>& matches) {
  remove_group(file_, pair_name);
  const Handle group = create_group(file_, pair_name, path_);
  std::vector<std::int32_t> matches0(static_cast<std::size_t>(keypoints0), -1);
  std::vector<float> scores0(static_cast<std::size_t>(keypoints0), 0.0f);
  for (const Match& m : matches) {
    matches0[static_cast<std::size_t>(m.query)] = m.train;
    scores0[static_cast<std::size_t>(m.query)] = 1.0f - static_cast<float>(m.distance) / 256.0f;
  }
  const hsize_t n = matches0.size();
  write_dataset(group.get(), "matches0", {n}, matches0, pair_name);
  write_dataset(group.get(), "matching_scores0", {n}, scores0, pair_name);  // last: marks the pair complete
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) throw Error("cannot flush '" + path_ + "' (disk full?)");
}

std::vector<Match> Hdf5File::read_matches(const std::string& pair_name) const {
  if (!exists(file_, pair_name)) throw Error("no pair '" + pair_name + "' in '" + path_ + "'");
  const Handle group(H5Gopen2(file_, pair_name.c_str(), H5P_DEFAULT), H5Gclose);
  std::vector<hsize_t> dims;
  const std::vector<std::int32_t> matches0 = read_dataset<std::int32_t>(group.get(), "matches0", dims, pair_name);
  std::vector<float> scores0(matches0.size(), 1.0f);
  if (exists(group.get(), "matching_scores0")) scores0 = read_dataset<float>(group.get(), "matching_scores0", dims, pair_name);
  if (scores0.size() != matches0.size()) throw Error("'" + pair_name + "' in '" + path_ + "': matches0 and matching_scores0 differ in length");
  std::vector<Match> matches;
  for (std::size_t i = 0; i < matches0.size(); ++i)
    if (matches0[i] >= 0)
      matches.push_back({static_cast<int>(i), matches0[i], static_cast<int>(std::lround((1.0f - scores0[i]) * 256.0f))});
  return matches;
}

std::vector<std::string> Hdf5File::feature_names() const {
  std::vector<std::string> names;
  const auto visit = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
    const std::string path(name);
    const std::string suffix = "/image_size";
    if (info->type == H5O_TYPE_DATASET && path.size() > suffix.size() && path.ends_with(suffix))
      static_cast<std::vector<std::string>*>(data)->push_back(path.substr(0, path.size() - suffix.size()));
    return 0;
  };
  if (H5Ovisit(file_, H5_INDEX_NAME, H5_ITER_INC, visit, &names) < 0) throw Error("cannot list the groups of '" + path_ + "'");
  std::sort(names.begin(), names.end());
  return names;
}

std::string hloc_pair_name(const std::string& name0, const std::string& name1) {
  std::string a = name0, b = name1;
  std::replace(a.begin(), a.end(), '/', '-');
  std::replace(b.begin(), b.end(), '/', '-');
  return a + "/" + b;
}

int merge_feature_files(const std::string& output, const std::vector<std::string>& inputs) {
  Hdf5File out(output, Hdf5File::Mode::read_write);
  std::vector<std::string> taken = out.feature_names();
  const std::size_t already = taken.size();
  int copied = 0;
  const Handle intermediate(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(intermediate.get(), 1);
  for (const std::string& input : inputs) {
    const Hdf5File in(input, Hdf5File::Mode::read);
    for (const std::string& name : in.feature_names()) {
      const auto end = taken.begin() + static_cast<std::ptrdiff_t>(already);
      if (std::find(taken.begin(), end, name) != end) continue;  // from an earlier merge into this output
      if (std::find(end, taken.end(), name) != taken.end())
        throw Error("image '" + name + "' is in two of the files merged (the second: '" + input + "')");
      remove_group(out.id(), name);
      if (H5Ocopy(in.id(), name.c_str(), out.id(), name.c_str(), H5P_DEFAULT, intermediate.get()) < 0)
        throw Error("cannot copy '" + name + "' from '" + input + "' into '" + output + "'");
      taken.push_back(name);
      ++copied;
    }
  }
  if (H5Fflush(out.id(), H5F_SCOPE_LOCAL) < 0) throw Error("cannot flush '" + output + "' (disk full?)");
  return copied;
}

}  // namespace aief::io

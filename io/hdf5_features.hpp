#pragma once
// Feature and match files in hloc's HDF5 layout (libhdf5's C API; built when libhdf5 is found,
// AIEF_HAVE_HDF5). hloc (github.com/cvg/Hierarchical-Localization) reads them as its own:
//
//   features.h5: one group per image, named by its path relative to the image folder (slashes
//   make nested groups, as h5py's create_group does), holding
//     keypoints    N x 2 float32, (x, y) with the centre of the top-left pixel at (0, 0): the
//                  OpenCV convention hloc uses in its files (hloc adds 0.5 when it writes COLMAP's
//                  database, whose origin is the top-left pixel's corner; io/colmap_database does too)
//     descriptors  32 x N uint8 (hloc stores descriptors dimension-first)
//     scores       N float32, the FAST response
//     image_size   2 int64, (width, height)
//   and, for aief's own readers, size, angle (degrees) and octave, N each, and source: 2 int64,
//   the image file's size in bytes and its modification time in nanoseconds (a batch resume
//   re-extracts an image whose file changed).
//   matches.h5: one group per pair, hloc's names_to_pair: name0 and name1 with '/' replaced by '-',
//   joined by '/', holding matches0 (N0 int32, the index in image 1 or -1) and matching_scores0
//   (N0 float32, 1 - distance / 256, 0 when unmatched). hloc writes int16 / float16; its readers
//   take any width, and int32 holds more than 32767 keypoints.
#include <memory>
#include <string>
#include <vector>

#include "aief/features.hpp"
#include "aief/match.hpp"
#include "io/source_record.hpp"

namespace aief::io {

// An HDF5 file opened for reading and writing (created when missing). Every write ends with a
// flush, and a group counts as complete only once its last dataset exists, so a killed batch
// resumes at the first incomplete image. Throws aief::Error naming the file.
class Hdf5File {
 public:
  enum class Mode { read, read_write };
  Hdf5File(const std::string& path, Mode mode);
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  const std::string& path() const { return path_; }
  long long id() const { return file_; }
  // Whether `name` is a complete image group (features) or pair group (matches).
  bool has_features(const std::string& name) const;
  bool has_matches(const std::string& pair_name) const;
  // Whether `name` is a complete image group written from the file `source` describes (same
  // size and modification time; a group written without a source never is).
  bool features_belong_to(const std::string& name, const SourceRecord& source) const;
  // Writes one image's group, replacing any group of that name; with `source`, records it.
  void write_features(const std::string& name, const Features& features, const SourceRecord* source = nullptr);
  // Removes an image's group, if there is one.
  void remove_features(const std::string& name);
  // Reads back what write_features wrote (keypoints, size, angle, octave, response, descriptors,
  // image size; info is not stored).
  Features read_features(const std::string& name) const;
  void write_matches(const std::string& pair_name, int keypoints0, const std::vector<Match>& matches);
  // The matches of a pair group (query = index in image 0); distance from matching_scores0.
  std::vector<Match> read_matches(const std::string& pair_name) const;
  // The image names of a features file: every group holding an image_size dataset, sorted.
  std::vector<std::string> feature_names() const;

 private:
  std::string path_;
  long long file_ = -1;  // hid_t
};

// hloc's names_to_pair(name0, name1): "a/b.png", "c.png" -> "a-b.png/c.png".
std::string hloc_pair_name(const std::string& name0, const std::string& name1);

// Copies every image group of `inputs` (shard files) into `output` (created or extended); an
// image already in `output` is kept, an image in two inputs is an error. Returns the images copied.
int merge_feature_files(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace aief::io

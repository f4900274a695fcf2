#pragma once
// The features of a features file's images that matching needs, read once and kept in memory up
// to a byte budget, the least recently used dropped first: `aief match --pairs` then reads each
// image once while its pairs come near each other (hloc's lists: sequential, retrieval,
// exhaustive), instead of both images for every pair. Descriptors only, unless the matcher needs
// the keypoints too (MatcherKind::guided). Built with HDF5.
#include <cstddef>
#include <list>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>

#include "aief/features.hpp"
#include "io/hdf5_file.hpp"

namespace aief::io {

class FeatureCache {
 public:
  // with_keypoints: read each image's keypoints besides its descriptors (Hdf5File::read_features),
  // else the descriptors alone (Hdf5File::read_descriptors; Features::keypoints stays empty).
  FeatureCache(const Hdf5File& file, std::size_t budget_bytes, bool with_keypoints)
      : file_(file), budget_(budget_bytes), with_keypoints_(with_keypoints) {}

  // The image's features (throws as the Hdf5File read). Valid while held: an entry dropped from
  // the cache lives on in the shared pointer.
  std::shared_ptr<const Features> get(const std::string& name);
  std::size_t reads() const { return reads_; }

 private:
  using Entry = std::pair<std::string, std::shared_ptr<const Features>>;
  static std::size_t bytes_of(const Entry& entry);
  const Hdf5File& file_;
  std::size_t budget_, held_ = 0, reads_ = 0;
  bool with_keypoints_;
  std::list<Entry> recent_;  // most recently used first
  std::unordered_map<std::string, std::list<Entry>::iterator> where_;
};

}  // namespace aief::io

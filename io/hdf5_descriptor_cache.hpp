#pragma once
// The descriptors of a features file's images, read once and kept in memory up to a byte budget,
// the least recently used dropped first: `aief match --pairs` then reads each image once while
// its pairs come near each other (hloc's lists: sequential, retrieval, exhaustive), instead of
// both images for every pair. Built with HDF5.
#include <cstddef>
#include <list>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "aief/features.hpp"
#include "io/hdf5_file.hpp"

namespace aief::io {

class DescriptorCache {
 public:
  using Descriptors = std::vector<Descriptor>;
  DescriptorCache(const Hdf5File& file, std::size_t budget_bytes)
      : file_(file), budget_(budget_bytes) {}

  // The image's descriptors (throws as Hdf5File::read_descriptors). Valid while held: an entry
  // dropped from the cache lives on in the shared pointer.
  std::shared_ptr<const Descriptors> get(const std::string& name);
  std::size_t reads() const { return reads_; }

 private:
  using Entry = std::pair<std::string, std::shared_ptr<const Descriptors>>;
  const Hdf5File& file_;
  std::size_t budget_, held_ = 0, reads_ = 0;
  std::list<Entry> recent_;  // most recently used first
  std::unordered_map<std::string, std::list<Entry>::iterator> where_;
};

}  // namespace aief::io

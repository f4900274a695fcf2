#include "io/hdf5_descriptor_cache.hpp"

namespace aief::io {

std::shared_ptr<const DescriptorCache::Descriptors> DescriptorCache::get(const std::string& name) {
  if (const auto found = where_.find(name); found != where_.end()) {
    recent_.splice(recent_.begin(), recent_, found->second);
    return found->second->second;
  }
  auto descriptors = std::make_shared<const Descriptors>(file_.read_descriptors(name));
  ++reads_;
  recent_.emplace_front(name, descriptors);
  where_[name] = recent_.begin();
  held_ += descriptors->size() * sizeof(Descriptor) + name.size();
  while (held_ > budget_ && recent_.size() > 1) {
    const Entry& oldest = recent_.back();
    held_ -= oldest.second->size() * sizeof(Descriptor) + oldest.first.size();
    where_.erase(oldest.first);
    recent_.pop_back();
  }
  return descriptors;
}

}  // namespace aief::io

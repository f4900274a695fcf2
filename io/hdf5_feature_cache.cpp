#include "io/hdf5_feature_cache.hpp"

namespace aief::io {

std::size_t FeatureCache::bytes_of(const Entry& entry) {
  const Features& f = *entry.second;
  return f.descriptors.size() * sizeof(Descriptor) + f.keypoints.size() * sizeof(Keypoint) +
         entry.first.size();
}

std::shared_ptr<const Features> FeatureCache::get(const std::string& name) {
  if (const auto found = where_.find(name); found != where_.end()) {
    recent_.splice(recent_.begin(), recent_, found->second);
    return found->second->second;
  }
  std::shared_ptr<Features> features;
  if (with_keypoints_) {
    features = std::make_shared<Features>(file_.read_features(name));
  } else {
    features = std::make_shared<Features>();
    features->descriptors = file_.read_descriptors(name);
  }
  ++reads_;
  recent_.emplace_front(name, features);
  where_[name] = recent_.begin();
  held_ += bytes_of(recent_.front());
  while (held_ > budget_ && recent_.size() > 1) {
    held_ -= bytes_of(recent_.back());
    where_.erase(recent_.back().first);
    recent_.pop_back();
  }
  return features;
}

}  // namespace aief::io

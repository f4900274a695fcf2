#include "tests/features_hash.hpp"

namespace aief::test {

std::uint64_t features_hash(const Features& features) {
  Fnv1a h;
  h.add_value(static_cast<std::uint64_t>(features.keypoints.size()));
  for (const Keypoint& kp : features.keypoints) {
    h.add_value(kp.x);
    h.add_value(kp.y);
    h.add_value(kp.size);
    h.add_value(kp.angle_deg);
    h.add_value(kp.response);
    h.add_value(kp.octave);
  }
  for (const Descriptor& d : features.descriptors) h.add(d.data(), d.size());
  h.add_value(features.info.entropy_threshold_used);
  h.add_value(features.info.blocks_kept);
  return h.value();
}

}  // namespace aief::test

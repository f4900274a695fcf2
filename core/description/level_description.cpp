#include "core/description/level_description.hpp"

#include <cassert>
#include <cstring>

namespace aief {

void LevelDescriptions::set_descriptor(DescriptorKind descriptor) {
  if (kind_of(descriptor_) != descriptor) descriptor_ = level_descriptor_of(descriptor);
}

void LevelDescriptions::start(const LevelGeometry& geometry, Selections selections) {
  std::visit([&](auto& descriptor) { descriptor.start(geometry, selections); }, descriptor_);
  memo_slot_.clear();
  memo_angle_deg_.clear();
  memo_descriptor_.clear();
}

std::size_t LevelDescriptions::slot(std::int32_t i) const {
  const std::int32_t slot = memo_slot_[static_cast<std::size_t>(i)];
  assert(slot >= 0);
  return static_cast<std::size_t>(slot);
}

bool LevelDescriptions::descriptor_input_ready() const {
  return std::visit([](const auto& descriptor) { return descriptor.whole_input_ready(); },
                    descriptor_);
}

void LevelDescriptions::prepare_descriptor_input(const PyramidLevel& level,
                                                 const KernelTable& kernels) {
  std::visit([&](auto& descriptor) { descriptor.prepare_whole_input(level, kernels); },
             descriptor_);
}

void LevelDescriptions::describe(const PyramidLevel& level,
                                 const std::vector<Candidate>& candidates,
                                 const std::vector<std::int32_t>& indices,
                                 const KernelTable& kernels) {
  points_.clear();
  todo_.clear();
  for (std::int32_t i : indices) {
    if (memo_slot_[static_cast<std::size_t>(i)] >= 0) continue;
    const Candidate& c = candidates[static_cast<std::size_t>(i)];
    points_.push_back({c.x, c.y});
    todo_.push_back(i);
  }
  if (todo_.empty()) return;
  const int count = static_cast<int>(todo_.size());
  angles_.resize(todo_.size());
  descriptors_.resize(todo_.size() * kDescriptorBytes);

  // Orientation on the raw level, descriptors on what the descriptor prepares (as ORB-SLAM2).
  keypoint_angles_.compute(kernels, level.pixels, points_.data(), count, orientation_,
                           angles_.data());
  std::visit(
      [&](auto& descriptor) {
        descriptor.describe(level, kernels, points_.data(), angles_.data(), count,
                            descriptors_.data());
      },
      descriptor_);
  for (int i = 0; i < count; ++i) {
    const std::size_t index = static_cast<std::size_t>(todo_[static_cast<std::size_t>(i)]);
    memo_slot_[index] = static_cast<std::int32_t>(memo_angle_deg_.size());
    memo_angle_deg_.push_back(angles_[static_cast<std::size_t>(i)]);
    Descriptor& descriptor = memo_descriptor_.emplace_back();
    std::memcpy(descriptor.data(),
                descriptors_.data() + static_cast<std::size_t>(i) * kDescriptorBytes,
                kDescriptorBytes);
  }
}

}  // namespace aief

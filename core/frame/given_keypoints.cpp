#include "core/frame/given_keypoints.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "aief/error.hpp"
#include "core/level/keypoint_position.hpp"

namespace aief {

std::string octave_fault(double octave, int n_levels) {
  if (!(std::floor(octave) == octave)) return "not an integer level";  // NaN too
  if (octave < 0 || octave >= n_levels)
    return "beyond the pyramid's levels 0.." + std::to_string(n_levels - 1);
  return "";
}

void check_given_keypoints(const std::vector<Keypoint>& keypoints, int n_levels,
                           GivenAngles angles) {
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const Keypoint& kp = keypoints[i];
    if (const std::string fault = octave_fault(kp.octave, n_levels); !fault.empty())
      throw Error("keypoint " + std::to_string(i) + " has octave " + std::to_string(kp.octave) +
                  ", " + fault);
    if (angles == GivenAngles::keep && !std::isfinite(kp.angle_deg))
      throw Error("keypoint " + std::to_string(i) + " has angle " + std::to_string(kp.angle_deg) +
                  " (degrees): the given angles are kept, so each must be a number");
  }
}

void describe_given_keypoints(FrameAnalysis& analysis, const KernelTable& kernels,
                              const std::vector<Keypoint>& keypoints, GivenAngles given_angles,
                              GivenKeypointScratch& scratch, Features& out,
                              std::vector<std::int32_t>* kept_indices) {
  const ExtractorOptions& options = analysis.options();
  const int levels = analysis.level_count();
  check_given_keypoints(keypoints, levels, given_angles);
  const int width0 = analysis.level(0).geometry.width, height0 = analysis.level(0).geometry.height;
  const std::size_t count = keypoints.size();

  // Each keypoint to its level pixel; the border rule (core/frame/given_keypoints.hpp) removes
  // some.
  scratch.level_members.resize(static_cast<std::size_t>(levels));
  for (std::vector<std::int32_t>& members : scratch.level_members) members.clear();
  scratch.level_pixel.resize(count);
  int deepest = -1;
  for (std::size_t i = 0; i < count; ++i) {
    const Keypoint& kp = keypoints[i];
    const PyramidLevel& level = analysis.level(kp.octave);
    if (!level.usable()) continue;
    const int w = level.geometry.width, h = level.geometry.height;
    const LevelToImage mapping = level_to_image(options.coordinates, options.subpixel,
                                                level.geometry.scale, width0, height0, w, h);
    const PixelPoint p = level_pixel({kp.x, kp.y}, mapping);
    if (p.x < kEdgeBorder || p.x >= w - kEdgeBorder || p.y < kEdgeBorder || p.y >= h - kEdgeBorder)
      continue;
    scratch.level_pixel[i] = p;
    scratch.level_members[static_cast<std::size_t>(kp.octave)].push_back(
        static_cast<std::int32_t>(i));
    deepest = std::max(deepest, kp.octave);
  }
  for (int n = 1; n <= deepest; ++n) analysis.build_level(n);  // a chain: level n from level n - 1

  scratch.angle_deg.resize(count);
  scratch.descriptor_row.assign(count, -1);
  scratch.descriptors.clear();
  if (kind_of(scratch.descriptor) != options.descriptor)
    scratch.descriptor = level_descriptor_of(options.descriptor);
  for (int n = 0; n <= deepest; ++n) {
    std::vector<std::int32_t>& members = scratch.level_members[static_cast<std::size_t>(n)];
    if (members.empty()) continue;
    const PyramidLevel& level = analysis.level(n);
    const int m = static_cast<int>(members.size());
    // Raster order, as the descriptor's band walks down the level (select() describes so too).
    const auto raster_before = [&](std::int32_t a, std::int32_t b) {
      const PixelPoint pa = scratch.level_pixel[static_cast<std::size_t>(a)];
      const PixelPoint pb = scratch.level_pixel[static_cast<std::size_t>(b)];
      return pa.y != pb.y ? pa.y < pb.y : pa.x < pb.x;
    };
    std::stable_sort(members.begin(), members.end(), raster_before);
    scratch.points.clear();
    for (std::int32_t i : members)
      scratch.points.push_back(scratch.level_pixel[static_cast<std::size_t>(i)]);
    // Orientation on the raw level, descriptors on what the descriptor prepares, as select() does.
    std::vector<float>& angles = scratch.level_angle_deg;
    angles.resize(members.size());
    if (given_angles == GivenAngles::recompute) {
      scratch.keypoint_angles.compute(kernels, level.pixels, scratch.points.data(), m,
                                      options.orientation, angles.data());
    } else {
      for (std::size_t k = 0; k < members.size(); ++k)
        angles[k] = keypoints[static_cast<std::size_t>(members[k])].angle_deg;
    }
    for (std::size_t k = 0; k < members.size(); ++k)
      scratch.angle_deg[static_cast<std::size_t>(members[k])] = angles[k];
    const std::size_t first_row = scratch.descriptors.size() / kDescriptorBytes;
    scratch.descriptors.resize((first_row + members.size()) * kDescriptorBytes);
    std::uint8_t* descriptors = scratch.descriptors.data() + first_row * kDescriptorBytes;
    for (std::size_t k = 0; k < members.size(); ++k)
      scratch.descriptor_row[static_cast<std::size_t>(members[k])] =
          static_cast<std::int32_t>(first_row + k);
    std::visit(
        [&](auto& descriptor) {
          descriptor.start(level.geometry, Selections::one);
          descriptor.describe(level, kernels, scratch.points.data(), angles.data(), m, descriptors);
        },
        scratch.descriptor);
  }

  out.image_width = width0;
  out.image_height = height0;
  out.info = ExtractionInfo{};
  out.descriptor = options.descriptor;
  out.keypoints.clear();
  out.descriptors.clear();
  if (kept_indices) kept_indices->clear();
  for (std::size_t i = 0; i < count; ++i) {
    const std::int32_t row = scratch.descriptor_row[i];
    if (row < 0) continue;
    Keypoint kp = keypoints[i];
    kp.angle_deg = scratch.angle_deg[i];
    out.keypoints.push_back(kp);
    Descriptor& descriptor = out.descriptors.emplace_back();
    std::memcpy(descriptor.data(),
                scratch.descriptors.data() + static_cast<std::size_t>(row) * kDescriptorBytes,
                kDescriptorBytes);
    if (kept_indices) kept_indices->push_back(static_cast<std::int32_t>(i));
  }
}

}  // namespace aief

#pragma once
// Pictures of results, written as PNG: keypoints over their image, matches side by side.
#include <string>
#include <vector>

#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/match.hpp"

namespace aief::io {

// Whether OpenCV writes a picture of this name: an extension it encodes (.png, .jpg, .bmp, .tif,
// .webp, ...), any case. The commands ask before any work.
bool is_picture_file_name(const std::string& path);

// Each keypoint a circle of its scale (colour by octave) with a line along its angle.
void draw_keypoints_png(const std::string& path, ImageView image, const Features& features);

// The two images side by side; inlier matches green, the others red.
void draw_matches_png(const std::string& path, ImageView a, const Features& features_a, ImageView b,
                      const Features& features_b, const std::vector<Match>& matches,
                      const std::vector<std::uint8_t>& inlier_mask);

}  // namespace aief::io

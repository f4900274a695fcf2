#pragma once
// The extractor: built once from options, then run on frame after frame. Buffers (pyramid,
// score maps, candidate lists) and the kernel table are kept between frames, so frames of one
// size allocate nothing after the first.
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"

namespace aief {

class Extractor {
 public:
  // Validates the options (throws aief::Error) and picks the kernel table.
  explicit Extractor(ExtractorOptions options = {});
  ~Extractor();
  Extractor(Extractor&&) noexcept;
  Extractor& operator=(Extractor&&) noexcept;

  // Keypoints and descriptors of one gray image. Throws aief::Error for an empty image or one
  // smaller than 2 * kEdgeBorder + 1 in either side.
  Features extract(ImageView image);
  // Same, into `out`, reusing its vectors' storage.
  void extract(ImageView image, Features& out);
  // With a detection mask: keypoints only where `mask` (the image's size) is non-zero, and the
  // budget filled there (docs/opencv.md says how the mask reaches each level). An empty mask is
  // no mask. Throws aief::Error for a mask of another size.
  void extract(ImageView image, ImageView mask, Features& out);

  // Descriptors of given keypoints (cv::Feature2D::compute), computed as for detected ones:
  // describing the keypoints extract() returned gives back its keypoints and descriptors bit for
  // bit. Each keypoint is described on the level its octave names, at its position mapped to
  // that level; its angle is recomputed (intensity centroid) or kept (GivenAngles) and its other
  // fields are kept. Keypoints closer than kEdgeBorder to their level's edge are removed (as
  // cv::ORB removes those near the image's edge); the rules are in docs/opencv.md. out.keypoints
  // holds the kept ones in their given order, out.info is left empty; kept_indices (when given)
  // receives each kept keypoint's index in `keypoints`. Throws aief::Error for an image
  // extract() refuses, an octave outside [0, n_levels), or a kept angle that is not finite.
  void describe(ImageView image, const std::vector<Keypoint>& keypoints, Features& out,
                std::vector<std::int32_t>* kept_indices = nullptr,
                GivenAngles angles = GivenAngles::recompute);
  Features describe(ImageView image, const std::vector<Keypoint>& keypoints,
                    GivenAngles angles = GivenAngles::recompute);

  // With options.carried_threshold (F carried through a video, docs/design.md §10): a sweep of
  // F starts with the next frame, on the pair (this frame, next frame), unless one runs (then
  // right after it). Does nothing in the other modes.
  void request_threshold_sweep();

  const ExtractorOptions& options() const;
  // Level n of the last frame's pyramid, valid until the next extract; empty for a level too
  // small to be built. Level 0 is the input image itself (not copied), so it is valid only as
  // long as the caller's pixels are. For callers that reuse the pyramid, as ORB-SLAM2's stereo
  // matching does.
  ImageView pyramid_level(int n) const;
  // Name of the kernel set that runs ("scalar", "avx2", ...).
  std::string_view kernel_name() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One-shot convenience: Extractor(options).extract(image).
Features extract(ImageView image, const ExtractorOptions& options = {});

}  // namespace aief

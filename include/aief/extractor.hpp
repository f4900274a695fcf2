#pragma once
// The extractor: built once from options, then run on frame after frame. Buffers (pyramid,
// score maps, candidate lists) and the kernel table are kept between frames, so frames of one
// size allocate nothing after the first.
#include <memory>
#include <string_view>

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

#include "aief/extractor.hpp"

#include <optional>

#include "core/frame/frame_pipeline.hpp"
#include "core/frame/given_keypoints.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/sweep/carried_threshold.hpp"

namespace aief {

struct Extractor::State {
  ExtractorOptions options;
  const KernelTable* kernels;
  FramePipeline pipeline;
  FrameAnalysis
      given_analysis;  // describe(): its own pyramid, so extract()'s stays for pyramid_level()
  GivenKeypointScratch given;
  std::optional<CarriedThreshold> carried;  // with options.carried_threshold

  void extract(ImageView image, ImageView mask, Features& out) {
    if (carried) pipeline.set_entropy_threshold(carried->threshold());
    pipeline.extract(image, out, nullptr, mask);
    if (carried) carried->after_frame(image);
  }
};

Extractor::Extractor(ExtractorOptions options) {
  options.validate();
  const KernelTable& kernels = kernel_table(options.kernels);
  state_ = std::make_unique<State>(
      State{options, &kernels, FramePipeline(options, kernels, options.threads), {}, {}, {}});
  if (options.carried_threshold && options.entropy != EntropyMeasure::off)
    state_->carried.emplace(options, kernels);
}

Extractor::~Extractor() = default;
Extractor::Extractor(Extractor&&) noexcept = default;
Extractor& Extractor::operator=(Extractor&&) noexcept = default;

const ExtractorOptions& Extractor::options() const { return state_->options; }

std::string_view Extractor::kernel_name() const { return state_->kernels->name; }

ImageView Extractor::pyramid_level(int n) const {
  const FrameAnalysis& analysis = state_->pipeline.analysis();
  if (n < 0 || n >= analysis.level_count() || !analysis.level(n).usable()) return {};
  return analysis.level(n).pixels;
}

Features Extractor::extract(ImageView image) {
  Features features;
  extract(image, features);
  return features;
}

void Extractor::extract(ImageView image, Features& out) { state_->extract(image, {}, out); }

void Extractor::extract(ImageView image, ImageView mask, Features& out) {
  state_->extract(image, mask, out);
}

void Extractor::request_threshold_sweep() {
  if (state_->carried) state_->carried->request_sweep();
}

void Extractor::describe(ImageView image, const std::vector<Keypoint>& keypoints, Features& out,
                         std::vector<std::int32_t>* kept_indices, GivenAngles angles) {
  State& s = *state_;
  check_given_keypoints(keypoints, s.options.n_levels, angles);  // before any pixel is read
  s.given_analysis.start(image, s.options, *s.kernels);
  describe_given_keypoints(s.given_analysis, *s.kernels, keypoints, angles, s.given, out,
                           kept_indices);
}

Features Extractor::describe(ImageView image, const std::vector<Keypoint>& keypoints,
                             GivenAngles angles) {
  Features features;
  describe(image, keypoints, features, nullptr, angles);
  return features;
}

Features extract(ImageView image, const ExtractorOptions& options) {
  return Extractor(options).extract(image);
}

}  // namespace aief

#include "aief/extractor.hpp"

#include "core/frame_pipeline.hpp"
#include "simd/kernels.hpp"

namespace aief {

struct Extractor::State {
  ExtractorOptions options;
  const KernelTable* kernels;
  FramePipeline pipeline;
};

Extractor::Extractor(ExtractorOptions options) {
  options.validate();
  const KernelTable& kernels = kernel_table(options.kernels);
  state_ = std::make_unique<State>(State{options, &kernels, FramePipeline(options, kernels, options.threads)});
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

void Extractor::extract(ImageView image, Features& out) { state_->pipeline.extract(image, out); }

Features extract(ImageView image, const ExtractorOptions& options) {
  return Extractor(options).extract(image);
}

}  // namespace aief

#include "core/sweep/carried_threshold.hpp"

#include <algorithm>
#include <cstring>

namespace aief {

namespace {

// The sweep's options: the extractor's, with F left to the sweep (and carry_every, which acts
// only with the carried F, at its default: core/options/acts_with.hpp).
ExtractorOptions sweep_options(ExtractorOptions options) {
  options.carried_threshold = false;
  options.auto_threshold = false;
  options.carry_every = ExtractorOptions{}.carry_every;
  return options;
}

void copy_into(ImageView frame, GrayImage& copy) {
  copy.resize(frame.width, frame.height);
  for (int y = 0; y < frame.height; ++y)
    std::memcpy(copy.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(frame.width),
                frame.row(y), static_cast<std::size_t>(frame.width));
}

}  // namespace

CarriedThreshold::CarriedThreshold(const ExtractorOptions& options, const KernelTable& kernels)
    : carry_every_(options.carry_every),
      n_features_(options.n_features),
      threshold_(options.entropy_threshold),
      sweep_(sweep_options(options), kernels) {}

bool CarriedThreshold::sweep_due() const {
  if (sweep_.running() || frame_index_ < 1) return false;  // one runs, or no pair yet
  return requested_ || last_start_ < 0 || frame_index_ - last_start_ >= carry_every_;
}

void CarriedThreshold::after_frame(ImageView frame) {
  if (sweep_due()) {
    start_sweep();
    std::swap(sweep_a_, previous_);  // the previous frame is A: no copy
    copy_into(frame, sweep_b_);
    sweep_.start(sweep_a_.view(), sweep_b_.view());
  }
  last_step_work_ = 0;
  last_step_pieces_ = 0;
  if (sweep_.running()) {
    const bool completed =
        sweep_.advance(SpreadSweep::frame_budget(frame, n_features_), last_sweep_);
    last_step_work_ = sweep_.last_work();
    last_step_pieces_ = sweep_.last_pieces();
    if (completed) {
      if (last_sweep_.found) threshold_ = last_sweep_.threshold;
      ++sweeps_completed_;
      last_completed_after_ = frame_index_;
    }
  }
  copy_into(frame, previous_);
  ++frame_index_;
}

void CarriedThreshold::start_sweep() {
  requested_ = false;
  last_start_ = frame_index_;
}

}  // namespace aief

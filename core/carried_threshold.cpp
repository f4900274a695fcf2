#include "core/carried_threshold.hpp"

#include <algorithm>
#include <cstring>

namespace aief {

namespace {

// The sweep's options: the extractor's, with F left to the sweep.
ExtractorOptions sweep_options(ExtractorOptions options) {
  options.carried_threshold = false;
  options.auto_threshold = false;
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
      threshold_(options.entropy_threshold),
      sweep_(sweep_options(options), SweepOptions{}, kernels) {}

bool CarriedThreshold::sweep_due() const {
  if (step_ >= 0 || frame_index_ < 1) return false;  // one runs, or no pair yet
  return requested_ || last_start_ < 0 || frame_index_ - last_start_ >= carry_every_;
}

void CarriedThreshold::after_frame(ImageView frame) {
  if (sweep_due()) {
    start_sweep();
    std::swap(sweep_a_, previous_);  // the previous frame is A: no copy
    copy_into(frame, sweep_b_);
  }
  if (step_ >= 0) run_step();
  copy_into(frame, previous_);
  ++frame_index_;
}

void CarriedThreshold::start_sweep() {
  requested_ = false;
  last_start_ = frame_index_;
  step_ = 0;
  thresholds_ = 0;
}

void CarriedThreshold::run_step() {
  if (step_ == 0) {
    sweep_.analyse(0, sweep_a_.view());
  } else if (step_ == 1) {
    sweep_.analyse(1, sweep_b_.view());
    thresholds_ = sweep_.begin_thresholds(Repeats::referenced);
  } else {
    const int first = (step_ - 2) * kThresholdsPerStep;
    const int end = std::min(thresholds_, first + kThresholdsPerStep);
    for (int c = first; c < end; ++c) {
      sweep_.select_threshold(0, c);
      sweep_.select_threshold(1, c);
      sweep_.evaluate_in_order(c);
    }
    if (end == thresholds_) {
      sweep_.choose(last_sweep_);
      if (last_sweep_.found) threshold_ = last_sweep_.threshold;
      ++sweeps_completed_;
      step_ = -1;
      return;
    }
  }
  ++step_;
}

}  // namespace aief

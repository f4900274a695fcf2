#pragma once
// F carried through a video (docs/design.md §10, "F carried through a video"): in a sequence
// there is always a previous frame, so the paper's adaptive sweep can choose F from the pair
// (previous frame, current frame) and the frames that follow use it.
//
// No frame waits for a sweep: it runs in steps, one step after each frame's own extraction, on
// the caller's thread (no background thread: every output stays a function of the frames alone,
// whatever the timing or the thread count). Step 0 analyses the previous frame, step 1 the
// current one, then each step selects, matches and fits kThresholdsPerStep thresholds of the
// sweep, and the last one chooses. A sweep that starts with frame t (pair t - 1, t) over C
// thresholds thus runs its steps after frames t .. t + 1 + ceil(C / kThresholdsPerStep), and its
// F applies from the next frame on (steps_of(C) frames after t). The answer is
// AdaptiveSweep::run's on that pair, bit for bit; a sweep with no eligible threshold keeps F.
//
// Sweeps start with frame 1 (the first pair), then every carry_every frames from one start to the
// next, and never while one runs; request_sweep() starts one with the next frame.
#include "aief/adapt.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/adaptive_sweep.hpp"
#include "core/kernel_table.hpp"

namespace aief {

class CarriedThreshold {
 public:
  // Thresholds of the sweep each step selects, matches and fits (with C <= 40 thresholds, at most
  // 10 threshold steps).
  static constexpr int kThresholdsPerStep = 4;
  // Steps of a sweep over C thresholds: the two analyses, then the thresholds.
  static int steps_of(int thresholds) {
    return 2 + (thresholds + kThresholdsPerStep - 1) / kThresholdsPerStep;
  }

  // `options` must be valid; F starts at options.entropy_threshold.
  CarriedThreshold(const ExtractorOptions& options, const KernelTable& kernels);

  // The F for the next frame.
  double threshold() const { return threshold_; }
  // After a frame's extraction: keeps a copy of it, starts a sweep on (previous frame, this
  // frame) when one is due, and runs the running sweep's next step.
  void after_frame(ImageView frame);
  // A sweep starts with the next frame (the pair: the frame before it and it), unless one runs;
  // then right after the one that runs.
  void request_sweep() { requested_ = true; }

  // For tests and records: frames seen, sweeps completed, and the last completed sweep's result.
  long long frames_seen() const { return frame_index_; }
  int sweeps_completed() const { return sweeps_completed_; }
  const AdaptResult& last_sweep() const { return last_sweep_; }

 private:
  bool sweep_due() const;
  void start_sweep();
  void run_step();

  int carry_every_;
  double threshold_;
  SweepPipeline sweep_;
  GrayImage previous_;           // the last frame, copied (the caller's pixels do not outlive it)
  GrayImage sweep_a_, sweep_b_;  // the running sweep's pair
  long long frame_index_ = 0;    // frames seen so far
  long long last_start_ = -1;    // frame index of the last sweep's start, -1 before the first
  bool requested_ = false;
  int step_ = -1;       // the running sweep's next step, -1 when none runs
  int thresholds_ = 0;  // C of the running sweep (after step 1)
  int sweeps_completed_ = 0;
  AdaptResult last_sweep_;
};

}  // namespace aief

#pragma once
// F carried through a video (docs/design.md §10, "F carried through a video"): in a sequence
// there is always a previous frame, so the paper's adaptive sweep can choose F from the pair
// (previous frame, current frame) and the frames that follow use it.
//
// No frame waits for a sweep, and no frame carries much of one: after each frame's extraction the
// running sweep advances by pieces whose estimated work fits SpreadSweep::frame_budget of that
// frame (core/sweep/spread_sweep.hpp: analyses a level at a time, descriptions and matching rows in
// runs), on the caller's thread (no background thread: every output stays a function of the
// frames alone, whatever the timing, kernel set or thread count). A sweep that starts with frame
// t (pair t - 1, t) thus runs after frames t, t + 1, ... until it completes (48-58 frames at
// 640x480, 1000 features), and its F applies from the frame after the one it completed with. The
// answer is AdaptiveSweep::run's on that pair, bit for bit; a sweep with no eligible threshold
// keeps F.
//
// Sweeps start with frame 1 (the first pair), then every carry_every frames from one start to the
// next, and never while one runs; request_sweep() starts one with the next frame.
#include "aief/adapt.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/sweep/spread_sweep.hpp"

namespace aief {

class CarriedThreshold {
 public:
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

  // For tests and records: frames seen, sweeps completed, the last completed sweep's result and
  // the index of the frame it completed after (its F applies from the next one), and the
  // estimated work the last frame's step did (core/sweep/spread_sweep.hpp).
  long long frames_seen() const { return frame_index_; }
  int sweeps_completed() const { return sweeps_completed_; }
  const AdaptResult& last_sweep() const { return last_sweep_; }
  long long last_sweep_completed_after() const { return last_completed_after_; }
  double last_step_work() const { return last_step_work_; }
  int last_step_pieces() const { return last_step_pieces_; }

 private:
  bool sweep_due() const;
  void start_sweep();

  int carry_every_;
  int n_features_;
  double threshold_;
  SpreadSweep sweep_;
  GrayImage previous_;           // the last frame, copied (the caller's pixels do not outlive it)
  GrayImage sweep_a_, sweep_b_;  // the running sweep's pair
  long long frame_index_ = 0;    // frames seen so far
  long long last_start_ = -1;    // frame index of the last sweep's start, -1 before the first
  bool requested_ = false;
  int sweeps_completed_ = 0;
  long long last_completed_after_ = -1;
  double last_step_work_ = 0;
  int last_step_pieces_ = 0;
  AdaptResult last_sweep_;
};

}  // namespace aief

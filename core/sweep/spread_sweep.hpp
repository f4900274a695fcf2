#pragma once
// The adaptive sweep of a pair (docs/design.md §10) spread over frames with a bound on each
// frame's share of it (docs/design.md §10, "F carried through a video";
// core/sweep/carried_threshold.hpp calls it once after each frame's extraction).
//
// The sweep is cut into pieces no larger than they must be: each image's analysis a pyramid level
// at a time, each threshold's selection a level at a time (distribution, the whole-level input the
// descriptors read, then the descriptions in runs of any length), each threshold's matching a
// row of new distances at a time (core/sweep/sweep_matcher.hpp), then RANSAC. Each piece's work is
// estimated beforehand from what it will read (pixels, candidates, descriptors, distances,
// matches), in units of about one AVX2 instruction; advance() runs pieces in order while their
// estimates fit the budget, and always at least one. The estimates depend only on the images, never
// on a clock or a kernel set, so the frame at which the sweep ends, and every output, is a function
// of the frames alone. The pieces are SweepPipeline's (core/sweep/adaptive_sweep.hpp), the ones its
// run() is made of: the answer is adapt()'s on the pair, bit for bit.
#include <cstddef>

#include "aief/adapt.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/sweep/adaptive_sweep.hpp"

namespace aief {

class SpreadSweep {
 public:
  // `options` must be valid and have an entropy measure (the sweep's F is its own).
  SpreadSweep(const ExtractorOptions& options, const KernelTable& kernels);

  // The work a frame of `image`'s size may add: kFrameShare of an estimated plain extraction of
  // n_features.
  static double frame_budget(ImageView image, int n_features);

  // A new sweep on the pair (a, b); both images must stay valid until it completes.
  void start(ImageView a, ImageView b);
  bool running() const { return phase_ != Phase::idle; }
  // Runs the next pieces while their estimated work fits `budget` (the first one always runs).
  // Returns true when the sweep completed with them; `out` then holds its result.
  bool advance(double budget, AdaptResult& out);
  // The estimated work and the pieces (those with work) of the last advance().
  double last_work() const { return last_work_; }
  int last_pieces() const { return last_pieces_; }

 private:
  enum class Phase {
    idle,
    entropies,         // image_, level_: its pixels and block entropies
    detect,            // image_, level_: its candidates at the sweep's lowest F
    begin_thresholds,  //
    select,            // image_ at c_: a repeat of c_ - 1, or its levels from level_ 0
    choose,            // image_, level_
    descriptor_input,  // image_, level_: the blurred level or integral image descriptors read
    describe,          // image_, level_
    finish_threshold,  // image_
    begin_evaluation,  // c_
    rows,              // c_
    finish_matching,   // c_
    fit,               // c_
  };
  // Runs the next piece if its estimate fits `room` (or `must`); returns its estimate, or a
  // negative number when it did not fit. Sets done_ when the sweep completed.
  double run_piece(double room, bool must, AdaptResult& out);
  void next_level_or(Phase after);
  // Image b when at image a, else `after`.
  void next_image_or(Phase after);
  void next_threshold(AdaptResult& out);

  SweepPipeline sweep_;
  std::size_t distribution_;  // the options' Distribution, for the estimates
  ImageView images_[2];
  Phase phase_ = Phase::idle;
  int image_ = 0, level_ = 0, c_ = 0, thresholds_ = 0;
  bool done_ = false;
  double last_work_ = 0;
  int last_pieces_ = 0;
};

}  // namespace aief

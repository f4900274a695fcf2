#pragma once
// Where a frame's time goes, stage by stage: a sink the frame pipeline
// (core/frame/frame_pipeline.hpp) adds to when it is given one (aief bench). Without a sink the
// pipeline reads no clock: the cost is one null test per stage call.
#include <array>
#include <cstddef>
#include <vector>

namespace aief {

enum class Stage {
  pyramid,  // level pixels from the level above (level 0 is the input)
  entropy,  // block histograms and entropies
  detect,   // FAST scores, maxima and candidates of the blocks F keeps
  select,   // distribution, orientation, blur and rBRIEF of the chosen candidates
  frame,    // once per frame: the automatic F, the fallback's frame rules, the output records
};
inline constexpr std::size_t kStageCount = 5;

class StageTimes {
 public:
  // Zeroes every stage.
  void clear() {
    for (std::array<double, kStageCount>& level : levels_) level.fill(0.0);
    frame_.fill(0.0);
  }
  // Adds `ms` to the stage of level n (n < 0: a frame-wide stage). Each (stage, level) is written
  // by one thread at a time, as the pipeline runs it: no lock.
  void add(Stage stage, int n, double ms) {
    std::array<double, kStageCount>& slot = n < 0 ? frame_ : levels_[static_cast<std::size_t>(n)];
    slot[static_cast<std::size_t>(stage)] += ms;
  }
  // Makes room for `levels` levels, keeping what was added.
  void reserve_levels(int levels) {
    if (static_cast<std::size_t>(levels) > levels_.size())
      levels_.resize(static_cast<std::size_t>(levels), {});
  }
  // Milliseconds in `stage` since clear(), summed over the levels (and so over the threads
  // that ran them side by side).
  double total_ms(Stage stage) const {
    double total = frame_[static_cast<std::size_t>(stage)];
    for (const std::array<double, kStageCount>& level : levels_)
      total += level[static_cast<std::size_t>(stage)];
    return total;
  }

 private:
  std::vector<std::array<double, kStageCount>> levels_;
  std::array<double, kStageCount> frame_{};
};

}  // namespace aief

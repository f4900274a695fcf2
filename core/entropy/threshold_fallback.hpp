#pragma once
// The threshold fallback: the entropy mask must not starve a frame (docs/design.md). The whole
// policy is here; the frame pipeline (core/frame/frame_pipeline.hpp) only asks it. The options'
// starvation_guard chooses the rules:
// - frame (the paper mode): lower F for the whole frame, by kStep down to 0, while all kept
//   blocks together hold fewer candidates than n_features. Blind to a level left empty while
//   others have plenty: with the automatic F, Otsu over all levels' blocks cuts the smooth coarse
//   levels first (levels 6-7 of a gravel-like texture got no keypoint, 867 of 1000 delivered).
// - level: each level lowers its own F while its kept blocks hold fewer candidates than its
//   budget N_n, so every level gets N_n whenever its blocks can give it at F = 0. Then the
//   shortfall: a level whose blocks hold fewer than N_n even so leaves the difference undelivered
//   (graf, --levels 20: 991 of 1000), and that difference goes to the levels with candidates to
//   spare, finest first (they have the most candidates and the most precise positions): the frame
//   delivers min(N, candidates in the kept blocks of every level).
// With entropy off there is no mask and no F to lower; the shortfall still applies.
#include <cstdint>
#include <vector>

#include "aief/options.hpp"

namespace aief {

// What the fallback reads and drives: detection of a frame's levels at a threshold F and the
// candidates in the blocks F keeps. FrameAnalysis through the pipeline; a table in the tests.
class CandidateSource {
 public:
  virtual int level_count() const = 0;
  // N_n: the features level n is asked for (0 for a level too small to use).
  virtual int level_budget(int n) const = 0;
  // Detects the blocks of level n that F keeps (only those not detected yet).
  virtual void detect_level(int n, double threshold) = 0;
  // The same for every level (levels may run in parallel).
  virtual void detect_frame(double threshold) = 0;
  // Candidates in the blocks of level n that F keeps (after detect at F).
  virtual std::int64_t level_candidates(int n, double threshold) const = 0;

 protected:
  ~CandidateSource() = default;
};

class ThresholdFallback {
 public:
  // Step by which a starving frame or level lowers F: the sweep's S_p (docs/design.md).
  static constexpr double kStep = 0.2;

  explicit ThresholdFallback(const ExtractorOptions& options);

  // First part, per level, as soon as its entropies are known: detects level n at `requested`
  // and, under the level rule, lowers the level's F while its kept blocks hold fewer candidates
  // than N_n and F > 0, detecting again at each step. Returns the level's F.
  double detect_level(CandidateSource& frame, int n, double requested) const;

  // Second part, once every level has detected at its F (`thresholds`, from detect_level) and
  // `budgets` hold N_n: the frame rule lowers every level's F to the frame's (detecting the
  // newly kept blocks), the shortfall raises budgets. Returns whether any F or budget changed:
  // then those levels select again. Rare; the first selections are usually final.
  bool settle_frame(CandidateSource& frame, double requested, std::vector<double>& thresholds,
                    std::vector<int>& budgets);

 private:
  bool level_rule_ = false, frame_rule_ = false, shortfall_rule_ = false;
  int n_features_ = 0;
  std::vector<std::int64_t> available_;
  std::vector<int> raised_;
};

// The shortfall's arithmetic: `budgets[n]` is N_n, `available[n]` the candidates in level n's
// kept blocks. Every level delivers min(budget, available); the sum of max(0, N_n - available_n)
// is handed out finest level first, each level taking at most available_n - N_n more. `raised`
// gets the new budgets (equal to `budgets` when there is no shortfall or no level can take it).
// Returns whether any budget was raised.
bool raise_budgets_for_shortfall(const std::vector<int>& budgets,
                                 const std::vector<std::int64_t>& available,
                                 std::vector<int>& raised);

}  // namespace aief

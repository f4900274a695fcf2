#pragma once
// The rows of the evaluation: our modes, with F as the mode sets it, swept over the pair or
// automatic, and OpenCV's ORB and SIFT as outside baselines. Each is run on one pair and measured
// the same way: our RANSAC (3 px) for inliers and CMR, the ground-truth homography for correct
// matches and accuracy.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "io/record_fields.hpp"
#include "tools/eval/timing.hpp"

#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"

namespace aief::eval {

// How an engine row chooses the entropy threshold F for a pair.
enum class ThresholdChoice {
  mode,       // as its mode sets it (F = 4, or no mask)
  swept,      // the adaptive sweep over the pair (aief adapt)
  automatic,  // pair-free: the automatic F of each image (--entropy-threshold auto)
};

// The rows that are not our engine.
// AKAZE and BRISK keep their 1000 strongest keypoints (cv::KeyPointsFilter::retainBest) before
// describing, so every row holds the same count; their binary descriptors (486 and 512 bits) are
// matched by OpenCV's Hamming matcher, mutual as ours.
enum class Baseline { none, opencv_orb, opencv_sift, opencv_akaze, opencv_brisk };

// A row of the evaluation: one of our modes with its way of choosing F, or an OpenCV baseline
// (its mode and threshold unused). The aief mode's rows take their options from
// EvalSettings::aief, the others the mode's own.
struct Method {
  Mode mode = Mode::aief;
  ThresholdChoice threshold = ThresholdChoice::mode;
  Baseline baseline = Baseline::none;
};
bool operator==(const Method& a, const Method& b);
inline bool operator!=(const Method& a, const Method& b) { return !(a == b); }

inline const std::vector<Method> kAllMethods = {
    {Mode::orbslam2},
    {Mode::quadtree_entropy},
    {Mode::aief_paper, ThresholdChoice::swept},  // --mode aief-paper: the paper's tables
    {Mode::aief_paper, ThresholdChoice::automatic},
    {Mode::aief, ThresholdChoice::swept},  // --mode aief (default): the measured departures
    {Mode::aief, ThresholdChoice::automatic},
    {Mode::aief, ThresholdChoice::mode, Baseline::opencv_orb},
    {Mode::aief, ThresholdChoice::mode, Baseline::opencv_sift},
    {Mode::aief, ThresholdChoice::mode, Baseline::opencv_akaze},
    {Mode::aief, ThresholdChoice::mode, Baseline::opencv_brisk}};

std::string method_name(const Method& method);  // the row label, e.g. "AIEF (adaptive F)"
// The JSON key, the mode's name with _adaptive or _auto, e.g. "aief_adaptive"; "opencv_orb".
std::string method_key(const Method& method);
// The row of kAllMethods with a JSON key; throws aief::Error for an unknown one.
Method parse_method_key(const std::string& key);

struct PairResult {
  int keypoints_a = 0, keypoints_b = 0;
  int putative = 0;     // matches before RANSAC (n of the paper)
  int inliers = 0;      // RANSAC inliers of our final model (m of the paper)
  double cmr = 0;       // m / n (Eq. 10)
  int correct = 0;      // putative matches within 3 px under the true homography
  double accuracy = 0;  // correct / putative (MMA@3px)
  double accuracy_1px = 0, accuracy_2px = 0;  // the share within 1 and 2 px (MMA@1px, MMA@2px)
  double corner_error =
      -1;  // mean corner error of the RANSAC homography vs the truth, px (-1: none)
  bool homography_ok = false;  // corner_error < 5 px
  double extract_ms =
      0;  // extraction + description of image A, one thread: CPU time, median of interleaved rounds
  double extract_min_ms = 0, extract_max_ms = 0;  // the fastest and slowest of those rounds
  double extract_wall_ms = 0;                     // the wall-clock median of the same rounds
  double sweep_ms = 0;       // the adaptive sweep over the pair (AIEF adaptive only)
  double threshold = -1;     // F used for image A (entropy methods)
  double repeatability = 0;  // keypoints of A repeated in B within 3 px (keypoint_metrics.hpp)
  double spread = 0;         // share of image A's 32 px cells holding a keypoint
};

}  // namespace aief::eval

// PairResult's one field list: its keys in aief eval's JSON (tools/eval/report.cpp), in order.
template <>
struct aief::io::RecordFields<aief::eval::PairResult> {
  using R = aief::eval::PairResult;
  static constexpr auto list = std::tuple{AIEF_RECORD_FIELD(keypoints_a),
                                          AIEF_RECORD_FIELD(keypoints_b),
                                          AIEF_RECORD_FIELD(putative),
                                          AIEF_RECORD_FIELD(inliers),
                                          AIEF_RECORD_FIELD(cmr),
                                          AIEF_RECORD_FIELD(correct),
                                          AIEF_RECORD_FIELD(accuracy),
                                          AIEF_RECORD_FIELD(accuracy_1px),
                                          AIEF_RECORD_FIELD(accuracy_2px),
                                          AIEF_RECORD_FIELD(corner_error),
                                          AIEF_RECORD_FIELD(homography_ok),
                                          AIEF_RECORD_FIELD(extract_ms),
                                          AIEF_RECORD_FIELD(extract_min_ms),
                                          AIEF_RECORD_FIELD(extract_max_ms),
                                          AIEF_RECORD_FIELD(extract_wall_ms),
                                          AIEF_RECORD_FIELD(sweep_ms),
                                          AIEF_RECORD_FIELD(threshold),
                                          AIEF_RECORD_FIELD(repeatability),
                                          AIEF_RECORD_FIELD(spread)};
};

namespace aief::eval {

struct EvalSettings {
  MatchOptions match;      // mutual by default
  int timing_repeats = 5;  // interleaved timing rounds per pair (timing.hpp)
  ExtractorOptions aief;   // the AIEF rows' options (the paper rows use --mode aief-paper)
};

// Every measure of one method on one pair but the extraction time.
PairResult run_method(const Method& method, const cv::Mat& gray_a, const cv::Mat& gray_b,
                      const Homography& truth, const EvalSettings& settings);
// The extraction times of image A for every method of `row` (results of run_method, in the order of
// `methods`; an adaptive method is timed at the F it chose), in interleaved rounds; `load` records
// the machine's load meanwhile.
void time_extractions(const std::vector<Method>& methods, const cv::Mat& gray_a,
                      const EvalSettings& settings, std::vector<PairResult>& row,
                      MachineLoad& load);

}  // namespace aief::eval

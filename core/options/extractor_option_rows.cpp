// ExtractorOptions' option rows (core/options/option_table.hpp), one per option in record order,
// with the few pieces of code they name (the mode's preset access, the setters of F and P).
// Adding one: CONTRIBUTING.md, "Adding an option". The value code that reads the rows (parsing,
// ranges, records, validate()) is in core/options/option_table.cpp.
#include <iterator>
#include <limits>
#include <string_view>
#include <vector>

#include "core/options/malformed_row.hpp"
#include "core/options/option_access.hpp"
#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"

namespace aief::option_table {

namespace {

using O = ExtractorOptions;  // AIEF_OPTION_ROW's struct

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The mode: a preset over the fields, no field of its own.
constexpr FieldAccess<ExtractorOptions> kPreset{ValueKind::choice, nullptr, nullptr,
                                                choices_of<Mode>};

// F, "auto" (the automatic threshold) or "carried" (F carried through a video).
void set_threshold(ExtractorOptions& options, const OptionValue& value) {
  const std::string_view* word = std::get_if<std::string_view>(&value);
  options.auto_threshold = word != nullptr && *word == "auto";
  options.carried_threshold = word != nullptr && *word == "carried";
  if (word == nullptr) options.entropy_threshold = std::get<double>(value);
}

// P, or "inf" / "off": no pool.
void set_pool(ExtractorOptions& options, const OptionValue& value) {
  options.candidate_pool =
      std::holds_alternative<std::string_view>(value) ? kInfinity : std::get<double>(value);
}

// The table. Record order is this order; the mode first.
constexpr OptionRow kRows[] = {
    {.key = "mode",
     .field = kPreset,
     .cli_flag = "--mode",
     .cli_value = "M",
     .python_keyword = "mode",
     .python_position = 2,
     .yaml_key = "ORBextractor.mode",
     .help = "named preset; aief-paper is the published algorithm to the byte (x * scale, "
             "no sub-pixel, no pool, frame-wide guard); orbslam2 keeps x * scale too"},
    {AIEF_OPTION_ROW(n_features), .cli_flag = "--n-features", .cli_value = "N",
     .python_keyword = "n_features", .python_position = 1, .yaml_key = "ORBextractor.nFeatures",
     .old_cli_flag = "--features", .help = "keypoints wanted over all levels", .low = 1,
     .high = 1000000},
    {AIEF_OPTION_ROW(scale_factor), .cli_flag = "--scale-factor", .cli_value = "S",
     .python_keyword = "scale_factor", .python_position = 5, .yaml_key = "ORBextractor.scaleFactor",
     .old_cli_flag = "--scale", .old_python_keyword = "scale",
     .help = "scale factor between levels", .low = 1, .high = 4, .low_is_open = true,
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "",
                  .quality = "1.1"}},
    {AIEF_OPTION_ROW(n_levels), .cli_flag = "--n-levels", .cli_value = "L",
     .python_keyword = "n_levels", .python_position = 4, .yaml_key = "ORBextractor.nLevels",
     .old_cli_flag = "--levels", .old_python_keyword = "levels", .help = "pyramid levels", .low = 1,
     .high = 32,
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "",
                  .quality = "18"}},
    {AIEF_OPTION_ROW(fast_threshold), .cli_flag = "--fast-threshold", .cli_value = "T",
     .python_keyword = "fast_threshold", .yaml_key = "ORBextractor.iniThFAST",
     .help = "FAST threshold tried first in a block", .low = 1, .high = 254},
    {AIEF_OPTION_ROW(fast_min_threshold), .cli_flag = "--fast-min-threshold", .cli_value = "T",
     .python_keyword = "fast_min_threshold", .yaml_key = "ORBextractor.minThFAST",
     .help = "retry threshold for a block without corners (at most the FAST threshold)", .low = 1,
     .high = 254},
    {AIEF_OPTION_ROW(block_size), .cli_flag = "--block-size", .cli_value = "B",
     .python_keyword = "block_size", .yaml_key = "ORBextractor.blockSize",
     .old_cli_flag = "--block", .help = "entropy / distribution block side, pixels", .low = 8,
     .high = 1024},
    {AIEF_OPTION_ROW(distribution), .help = "set by the mode",
     .per_mode = {.aief = "default",
                  .aief_paper = "proportional",
                  .orbslam2 = "quadtree",
                  .quadtree_entropy = "quadtree",
                  .faithful = "quadtree",
                  .quality = "default"}},
    {AIEF_OPTION_ROW(entropy), .cli_flag = "--entropy", .cli_value = "E",
     .python_keyword = "entropy", .yaml_key = "ORBextractor.entropy",
     .help = "what a block's entropy measures; off: no mask",
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "=off",
                  .quadtree_entropy = "",
                  .faithful = "=off",
                  .quality = "off"}},
    {AIEF_OPTION_ROW_WITH_SET(entropy_threshold, set_threshold), .cli_flag = "--entropy-threshold",
     .cli_value = "F|auto|carried", .python_keyword = "entropy_threshold", .python_position = 3,
     .yaml_key = "ORBextractor.entropyThreshold", .old_cli_flag = "--threshold",
     .old_python_keyword = "threshold",
     .help = "entropy threshold F in bits (a block is kept when its entropy is > F); "
             "auto: Otsu's split of the frame's own block entropies; "
             "carried: the adaptive sweep on the previous and current frames every "
             "--carry-every frames, spread over the frames that follow "
             "(F = 4 until the first sweep ends)",
     .low = 0, .high = 64, .words = "auto|carried", .needs_mask = "sets F of the entropy mask",
     .read_by_sweep = false},
    {AIEF_OPTION_ROW(auto_threshold), .help = "set by --entropy-threshold auto", .words = "on|off",
     .read_by_sweep = false},
    {AIEF_OPTION_ROW(carried_threshold), .help = "set by --entropy-threshold carried",
     .words = "on|off", .read_by_sweep = false},
    {AIEF_OPTION_ROW(carry_every), .cli_flag = "--carry-every", .cli_value = "N",
     .python_keyword = "carry_every", .yaml_key = "ORBextractor.carryEvery",
     .help = "with --entropy-threshold carried: "
             "frames from the start of one sweep to the start of the next "
             "(a sweep never starts while one runs)",
     .low = 1, .high = 1000000, .needs_mask = "sets how often the carried F is swept",
     .acts_with = "carried_threshold=on"},
    {AIEF_OPTION_ROW(coordinates), .cli_flag = "--coordinates", .cli_value = "C",
     .python_keyword = "coordinates", .yaml_key = "ORBextractor.coordinates",
     .help = "a keypoint's level-0 position: "
             "pixel-centre (x + 0.5) * W0 / Wn - 0.5, or scaled x * scale^n",
     .per_mode = {.aief = "default",
                  .aief_paper = "scaled",
                  .orbslam2 = "scaled",
                  .quadtree_entropy = "scaled",
                  .faithful = "scaled",
                  .quality = "default"}},
    {AIEF_OPTION_ROW(subpixel), .cli_flag = "--subpixel", .cli_value = "on|off",
     .python_keyword = "subpixel", .yaml_key = "ORBextractor.subpixel",
     .help = "parabola peak of the FAST scores per axis", .words = "on|off",
     .per_mode = {.aief = "default",
                  .aief_paper = "off",
                  .orbslam2 = "off",
                  .quadtree_entropy = "off",
                  .faithful = "off",
                  .quality = "default"}},
    {AIEF_OPTION_ROW_WITH_SET(candidate_pool, set_pool), .cli_flag = "--candidate-pool",
     .cli_value = "P|inf", .python_keyword = "candidate_pool",
     .yaml_key = "ORBextractor.candidatePool", .old_cli_flag = "--pool",
     .old_python_keyword = "pool",
     .help = "candidate pool: each level keeps its best ceil(P x N_level) candidates before the "
             "water-level distribution; inf (or off): none",
     .low = 1, .high = kInfinity, .words = "inf|off",
     .per_mode = {.aief = "default",
                  .aief_paper = "inf",
                  .orbslam2 = "inf",
                  .quadtree_entropy = "inf",
                  .faithful = "inf",
                  .quality = "default"},
     .acts_with = "distribution=proportional"},
    {AIEF_OPTION_ROW(candidate_ranking), .cli_flag = "--candidate-ranking", .cli_value = "R",
     .python_keyword = "candidate_ranking", .yaml_key = "ORBextractor.candidateRanking",
     .old_cli_flag = "--ranking", .old_python_keyword = "ranking",
     .old_yaml_key = "ORBextractor.ranking",
     .help = "what the pool and the distribution rank candidates by: "
             "cross = FAST scores summed over the corner and its 4 neighbours, "
             "peak = the corner's score",
     .per_mode = {.aief = "default",
                  .aief_paper = "peak",
                  .orbslam2 = "peak",
                  .quadtree_entropy = "peak",
                  .faithful = "peak",
                  .quality = "default"},
     .acts_with = "detection_cells=blocks"},
    {AIEF_OPTION_ROW(starvation_guard), .cli_flag = "--starvation-guard", .cli_value = "G",
     .python_keyword = "starvation_guard", .yaml_key = "ORBextractor.starvationGuard",
     .help = "level: F lowered per level until it has its budget, "
             "what a level still lacks going to the levels with candidates to spare, "
             "finest first; frame: F lowered for the whole frame until it has n_features",
     .per_mode = {.aief = "default",
                  .aief_paper = "frame",
                  .orbslam2 = "frame",
                  .quadtree_entropy = "frame",
                  .faithful = "frame",
                  .quality = "default"},
     .read_by_sweep = false},
    {AIEF_OPTION_ROW(auto_skips_uniform_blocks), .cli_flag = "--auto-uniform-blocks",
     .cli_value = "skip|count", .python_keyword = "auto_skips_uniform_blocks",
     .yaml_key = "ORBextractor.autoUniformBlocks",
     .help = "whether one-gray-level blocks take part in the automatic F", .words = "skip|count",
     .per_mode = {.aief = "default",
                  .aief_paper = "count",
                  .orbslam2 = "count",
                  .quadtree_entropy = "count",
                  .faithful = "count",
                  .quality = "default"},
     .acts_with = "auto_threshold=on"},
    {AIEF_OPTION_ROW(auto_requires_two_classes), .cli_flag = "--auto-requires-two-classes",
     .cli_value = "on|off", .python_keyword = "auto_requires_two_classes",
     .yaml_key = "ORBextractor.autoRequiresTwoClasses", .old_cli_flag = "--auto-two-classes",
     .old_yaml_key = "ORBextractor.autoTwoClasses",
     .help = "automatic F: split only when the block entropies form two classes "
             "(Otsu's effectiveness >= 0.75), else F = 0 keeps every block",
     .words = "on|off",
     .per_mode = {.aief = "default",
                  .aief_paper = "off",
                  .orbslam2 = "off",
                  .quadtree_entropy = "off",
                  .faithful = "off",
                  .quality = "default"},
     .acts_with = "auto_threshold=on"},
    {AIEF_OPTION_ROW(pyramid_resampling), .cli_flag = "--pyramid-resampling", .cli_value = "R",
     .python_keyword = "pyramid_resampling", .yaml_key = "ORBextractor.pyramidResampling",
     .old_cli_flag = "--pyramid", .old_python_keyword = "pyramid",
     .old_yaml_key = "ORBextractor.pyramid",
     .help = "how a level is resampled from the one above: "
             "q8 (the engine's vector kernels) or opencv (cv::resize INTER_LINEAR to the byte, "
             "ORB-SLAM's pixels; scalar)",
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "opencv",
                  .quality = ""}},
    {AIEF_OPTION_ROW(detection_cells), .cli_flag = "--detection-cells", .cli_value = "C",
     .python_keyword = "detection_cells", .yaml_key = "ORBextractor.detectionCells",
     .help = "where the FAST retry and suppression act: "
             "blocks (the engine's, suppression over the level) or orbslam "
             "(ORB-SLAM3's 35-pixel cells, each its own image)",
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "orbslam",
                  .quality = ""}},
    {AIEF_OPTION_ROW(quadtree_ties), .cli_flag = "--quadtree-ties", .cli_value = "T",
     .python_keyword = "quadtree_ties", .yaml_key = "ORBextractor.quadtreeTies",
     .help = "how the quadtree breaks ties: "
             "full (written tie-break, exactly N per level) or orbslam (ORB-SLAM's list order, "
             "up to N + 3 per level); the unweighted quadtree only",
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "orbslam",
                  .quality = ""},
     .acts_with = "distribution=quadtree,quadtree_weight=none"},
    {AIEF_OPTION_ROW(orientation), .cli_flag = "--orientation", .cli_value = "O",
     .python_keyword = "orientation", .yaml_key = "ORBextractor.orientation",
     .help = "the angle of the intensity centroid: "
             "atan2 (in double) or fast-atan2 (cv::fastAtan2, ORB-SLAM's, "
             "about 0.01 degrees off)",
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "fast-atan2",
                  .quality = ""}},
    {AIEF_OPTION_ROW(quadtree_weight), .cli_flag = "--quadtree-weight", .cli_value = "W",
     .python_keyword = "quadtree_weight", .yaml_key = "ORBextractor.quadtreeWeight",
     .help = "what orders the quadtree's splits: "
             "none (every node each round) or entropy "
             "(the node whose candidates' block entropies sum highest splits next; "
             "every leaf keeps its strongest); the quadtree only",
     .acts_with = "distribution=quadtree"},
    {AIEF_OPTION_ROW(fast_threshold_from), .cli_flag = "--fast-threshold-from", .cli_value = "S",
     .python_keyword = "fast_threshold_from", .yaml_key = "ORBextractor.fastThresholdFrom",
     .help = "a block's first FAST threshold: "
             "none (the FAST threshold) or entropy "
             "(from the retry threshold at 0 bits up to the FAST threshold at 6 bits, "
             "linearly); the engine's blocks only",
     .acts_with = "detection_cells=blocks"},
    {AIEF_OPTION_ROW(low_entropy_sharpen), .cli_flag = "--low-entropy-sharpen",
     .cli_value = "on|off", .python_keyword = "low_entropy_sharpen",
     .yaml_key = "ORBextractor.lowEntropySharpen",
     .help = "FAST detects on the level with its low-entropy blocks sharpened (unsharp mask, "
             "amount 2 at 0 bits falling linearly to none at 6 bits, blended between blocks); "
             "orientation and descriptors read the level as it is",
     .words = "on|off"},
    {AIEF_OPTION_ROW(descriptor), .cli_flag = "--descriptor", .cli_value = "D",
     .python_keyword = "descriptor", .yaml_key = "ORBextractor.descriptor",
     .help = "the 256-bit descriptor: "
             "rbrief (ORB's learned pattern on the blurred level) or box "
             "(learned box-average tests on the level's integral image, TEBLID's form; "
             "a SLAM vocabulary trained on rbrief needs retraining for it); "
             "files of different descriptors never match",
     .per_mode = {.aief = "",
                  .aief_paper = "",
                  .orbslam2 = "",
                  .quadtree_entropy = "",
                  .faithful = "",
                  .quality = "box"}},
    {AIEF_OPTION_ROW(detection_smoothing), .cli_flag = "--detection-smoothing",
     .cli_value = "SIGMA", .python_keyword = "detection_smoothing",
     .yaml_key = "ORBextractor.detectionSmoothing",
     .help = "FAST detects on each level blurred by round(SIGMA^2) passes of the 5x5 binomial "
             "(sigma 1 each): SIGMA 1, 1.5, 1.8, 2, 2.3, 2.5, 2.7, 2.9 or 3, "
             "one value for each number of passes; "
             "orientation and descriptors read the level as it is; 0: off",
     .low = 0, .high = 3,
     .per_mode = {.aief = "default",
                  .aief_paper = "default",
                  .orbslam2 = "default",
                  .quadtree_entropy = "default",
                  .faithful = "default",
                  .quality = "1.5"}},
    {AIEF_OPTION_ROW(scale_selection), .cli_flag = "--scale-selection", .cli_value = "S",
     .python_keyword = "scale_selection", .yaml_key = "ORBextractor.scaleSelection",
     .help = "which levels keep a corner FAST finds on several: "
             "off (every level its copy) or extrema "
             "(a candidate stays only where no candidate of an adjacent level at the same place "
             "is stronger); the engine's blocks only",
     .acts_with = "detection_cells=blocks", .read_by_sweep = false},
    {AIEF_OPTION_ROW(kernels), .cli_flag = "--kernels", .cli_value = "K",
     .python_keyword = "kernels", .python_position = 7, .yaml_key = "ORBextractor.kernels",
     .help = "the pixel kernels' instruction set; every set gives the same output",
     .changes_output = false},
    {AIEF_OPTION_ROW(threads), .cli_flag = "--threads", .cli_value = "T",
     .python_keyword = "threads", .python_position = 6, .yaml_key = "ORBextractor.threads",
     .help = "worker threads, 0 = all cores; any count gives the same output", .low = 0,
     .high = 256, .changes_output = false},
    {AIEF_OPTION_ROW(max_image_pixels), .cli_flag = "--max-image-pixels", .cli_value = "N",
     .python_keyword = "max_image_pixels", .yaml_key = "ORBextractor.maxImagePixels",
     .help = "largest image accepted, in pixels, refused before any allocation (at most 2^26: "
             "the exact entropy sums)",
     .low = 1, .high = static_cast<double>(kLargestMaxImagePixels), .changes_output = false},
};
AIEF_CHECK_OPTION_ROWS(kRows);

}  // namespace

template <>
const std::vector<Row<ExtractorOptions>>& rows_of<ExtractorOptions>() {
  static const std::vector<OptionRow> table(std::begin(kRows), std::end(kRows));
  return table;
}

}  // namespace aief::option_table

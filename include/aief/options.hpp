#pragma once
// Options of the extractor. Defaults are docs/design.md §1 (ORB-SLAM2's settings); no other
// file repeats them: the CLI, the JSON writer and the tests read them from these structs.
#include <string>
#include <string_view>

#include "aief/error.hpp"  // what the functions below throw

namespace aief {

// How the keypoints of a level are spread over its blocks (docs/design.md §6).
enum class Distribution {
  proportional,  // AIEF, Eq. 12-17: every block keeps min(R_i, k) for a water level k
  quadtree,      // ORB-SLAM2's DistributeOctTree with a full tie-break
};

// Which entropy a block is measured by.
enum class EntropyMeasure {
  off,        // no entropy mask: every block is kept (ORB-SLAM2)
  histogram,  // Shannon entropy of the block's 256-bin gray histogram, bits (default)
  intensity,  // the paper's literal Eq. 5-6: p_ij = f(i,j) / sum f
};

// Instruction set of the pixel kernels. Every set gives the same bytes (docs/design.md §12).
enum class KernelSet {
  auto_select,  // the best the CPU supports
  scalar,       // the reference in core/
  sse4_2,
  avx2,
  avx512bw,
  neon64,  // AArch64 Advanced SIMD
};

// Where a level point lands in level-0 pixels (core/level/keypoint_position.hpp).
enum class CoordinateMap {
  scaled,        // x * scale_factor^n: the paper and ORB-SLAM2 (biased at coarse levels)
  pixel_centre,  // (x + 0.5) * (W_0 / W_n) - 0.5 per axis: where the pyramid sampled the point
};

// What keeps a frame's entropy mask from starving it of keypoints.
enum class StarvationGuard {
  frame,  // lower F for the whole frame while all kept blocks hold < n_features candidates
  level,  // lower F per level while the level's kept blocks hold < its budget N_n
};

// What a level ranks its candidates by, in the candidate pool and the distribution.
enum class CandidateRanking {
  peak_score,   // the FAST score of the corner pixel (ORB-SLAM2, the paper)
  cross_score,  // FAST scores summed over the corner and its 4 neighbours (docs/design.md §6)
};

// How a pyramid level is resampled from the level above (docs/design.md §2).
enum class PyramidResampling {
  q8,      // the engine's Q8 bilinear, vector kernels (core/kernels/resize_bilinear_rows.hpp)
  opencv,  // cv::resize INTER_LINEAR to the byte: ORB-SLAM's pixels
           // (core/kernels/resize_opencv_linear_rows)
};

// Where detection's threshold retry and non-maximum suppression act (docs/design.md §5).
enum class DetectionCells {
  blocks,   // the engine's blocks, suppression over the whole level
            // (core/detection/level_detection.hpp)
  orbslam,  // ORB-SLAM3's 35-pixel cells, each suppressed as its own image
            // (core/detection/orbslam_cells.hpp)
};

// How the quadtree breaks ties (docs/design.md §6).
enum class QuadtreeTies {
  full,     // a written tie-break for every ordering, exactly N per level
            // (core/distribution/distribution.hpp)
  orbslam,  // ORB-SLAM's list order and overshoot of up to 3 (core/distribution/octree_orbslam.hpp)
};

// Where a block's first FAST threshold comes from (docs/design.md §5).
enum class FastThresholdFrom {
  none,     // fast_threshold in every block (ORB-SLAM's iniThFAST)
  entropy,  // fast_min_threshold up to fast_threshold by block entropy
            // (core/entropy/entropy_fast_threshold)
};

// What weights the quadtree's splits (docs/design.md §6).
enum class QuadtreeWeight {
  none,     // every node splits each round (distribute_quadtree / ORB-SLAM's octree)
  entropy,  // the node of the largest block-entropy weight splits next
            // (core/distribution/quadtree_weighted)
};

// The angle of the intensity centroid (docs/design.md §7).
enum class Orientation {
  atan2,        // atan2 in double, rounded to float
  opencv_fast,  // cv::fastAtan2 in float, ORB-SLAM's IC_Angle (core/kernels/fast_atan2.hpp)
};

// What describes a keypoint (docs/design.md §7 and "The box descriptor"). Both are 256 bits,
// Hamming-matched; descriptors of one kind never match the other's.
enum class DescriptorKind {
  rbrief,  // rBRIEF with the learned ORB pattern on the blurred level (ORB, ORB-SLAM)
  box,     // 256 learned box-average tests on the level's integral image (TEBLID's form,
           // core/kernels/box_describe.hpp)
};

// Which pyramid level keeps a corner that FAST finds on several (docs/design.md §5, "Scale
// selection").
enum class ScaleSelection {
  off,      // every level keeps its own candidates, each level its budget N_n (ORB, ORB-SLAM)
  extrema,  // a candidate stays only where its strength is not beaten by a candidate of an
            // adjacent level at the same place (core/detection/scale_selection.hpp)
};

// Named presets over ExtractorOptions, the rows of the paper's tables.
enum class Mode {
  aief,        // AIEF with seven measured departures (docs/design.md §11; the defaults below)
  aief_paper,  // AIEF exactly as published: x * scale, no sub-pixel, no pool, frame guard
  orbslam2,    // quadtree, no entropy, ORB-SLAM2's conventions (x * scale)
  quadtree_entropy,  // quadtree + entropy mask, the paper's conventions
  faithful,          // orbslam2 with ORB-SLAM's own pyramid pixels, cells, octree tie-breaks and
                     // orientation
  quality,           // aief with FAST on smoothed levels, a finer pyramid (1.1, 18 levels), the
                     // box descriptor and no entropy mask: for hard pairs (blur, scale),
                     // docs/evaluation.md "Hard families"; for SfM, docs/colmap.md
};

struct ExtractorOptions {
  int n_features = 1000;       // keypoints wanted over all levels (ORB-SLAM2 nFeatures)
  double scale_factor = 1.2;   // size ratio between two pyramid levels (ORB-SLAM2 scaleFactor)
  int n_levels = 8;            // pyramid levels (ORB-SLAM2 nLevels)
  int fast_threshold = 20;     // FAST-9 threshold tried first in a block (ORB-SLAM2 iniThFAST)
  int fast_min_threshold = 7;  // retry threshold when a block has no corner (ORB-SLAM2 minThFAST)
  int block_size = 32;         // side of an entropy / distribution block, level pixels
  Distribution distribution = Distribution::proportional;
  EntropyMeasure entropy = EntropyMeasure::histogram;
  // F of Eq. 9: a block is kept when its entropy is > F. 4.0 bits keeps textured blocks and
  // drops sky, walls and saturated areas on the Oxford images; `adapt` chooses F per scene.
  double entropy_threshold = 4.0;
  // Pair-free automatic F (core/frame/auto_threshold.hpp) instead of entropy_threshold: Otsu's
  // split of the frame's own block entropies. `aief extract --entropy-threshold auto`.
  bool auto_threshold = false;
  // F carried through a video (core/sweep/carried_threshold.hpp, docs/design.md §10): the
  // extractor runs the adaptive sweep on the pair (previous frame, current frame) every
  // carry_every frames, spread over the following frames, and applies the F it chooses from the
  // frame after it ends; entropy_threshold until then. `aief extract --entropy-threshold carried`.
  bool carried_threshold = false;
  // Frames from the start of one carried sweep to the start of the next (at least the frames a
  // sweep takes: a sweep never starts while one runs). 30: a sweep takes 12 frames at most
  // (core/sweep/carried_threshold.hpp), so the frames pay for one every 30 (docs/design.md §10).
  int carry_every = 30;
  // Level-0 position of a keypoint. The pyramid is pixel-centre aligned, so x * scale is off by
  // 3-8 px at levels 6-7 (docs/design.md §8); the paper and ORB-SLAM2 modes keep it for fidelity.
  CoordinateMap coordinates = CoordinateMap::pixel_centre;
  // Refine each keypoint to sub-pixel by a 3-point parabola per axis on the FAST score map.
  bool subpixel = true;
  // P of the candidate pool: with the proportional distribution each level first keeps its
  // strongest ceil(P * N_n) candidates over the kept blocks, then distributes them by the water
  // level; infinity = no pool (the paper). 1.25: a quarter more than the budget, so the water level
  // still chooses; measured against 1, 1.1, 1.5, 2, 3 and none in docs/evaluation.md.
  double candidate_pool = 1.25;
  // Ranking of candidates in the pool and the distribution (ties: peak score, then y, then x).
  // A single pixel's FAST score is the extreme of a noisy max-min test; a real corner keeps a
  // response on the pixels beside it, so the sum over the cross measures its strength over an area
  // (as Harris integrates over a window) at no extra pass: the scores are in the score map.
  CandidateRanking candidate_ranking = CandidateRanking::cross_score;
  // With entropy on: per level (each level gets its budget when its blocks can give it) or
  // frame-wide (the paper mode's rule). With `level`, what a level still lacks (its kept blocks
  // hold fewer candidates than its budget, entropy on or off) goes to the levels with unselected
  // candidates, finest first: the frame gets min(n_features, candidates in the kept blocks).
  StarvationGuard starvation_guard = StarvationGuard::level;
  // Automatic F: uniform blocks (one gray level: the black border of a warped image, saturated
  // sky) cannot hold a corner and are left out of Otsu's split. false: every block counts.
  bool auto_skips_uniform_blocks = true;
  // Automatic F: Otsu's split only when the block entropies fall into two classes, i.e. when its
  // effectiveness (between-class over total variance) reaches kAutoMinEffectiveness
  // (core/frame/auto_threshold.hpp); otherwise the frame has no low-information class and F = 0
  // keeps every block. false: always Otsu's split (capped to keep three quarters of the blocks).
  bool auto_requires_two_classes = true;
  // The choices of the faithful mode, each on its own for measurement: ORB-SLAM3's ORBextractor
  // to the keypoint (docs/design.md §2, §5, §6, §7). The octree ties act on the quadtree only;
  // ORB-SLAM's cells take no detection mask (the entropy mask then drops their candidates by
  // block).
  PyramidResampling pyramid_resampling = PyramidResampling::q8;
  DetectionCells detection_cells = DetectionCells::blocks;
  QuadtreeTies quadtree_ties = QuadtreeTies::full;
  Orientation orientation = Orientation::atan2;
  // Entropy-guided variant, the quadtree only: its splits weighted by block entropy
  // (the entropy measure's, histogram when the mask is off), every leaf keeping its strongest.
  QuadtreeWeight quadtree_weight = QuadtreeWeight::none;
  // Entropy-guided variant, the engine's blocks only (not ORB-SLAM's cells): a block's
  // first FAST threshold falls with its entropy, so weak-texture and dark blocks keep weaker
  // corners; the retry at fast_min_threshold stays.
  FastThresholdFrom fast_threshold_from = FastThresholdFrom::none;
  // Entropy-guided variant: FAST detects on a copy of each level whose low-entropy blocks are
  // sharpened (an unsharp mask whose amount falls with the block's entropy, blended between
  // blocks; core/entropy/low_entropy_sharpen.hpp); orientation and descriptors read the level
  // itself.
  bool low_entropy_sharpen = false;
  // The descriptor. rbrief in every mode but quality (ORB-SLAM's vocabularies are trained on it);
  // box is the learned box descriptor (a vocabulary trained on rBRIEF needs retraining for it).
  DescriptorKind descriptor = DescriptorKind::rbrief;
  // Detection on a smoothed level (core/detection/detection_smoothing.hpp): FAST reads each level
  // (its sharpened copy with low_entropy_sharpen) blurred to about this sigma, px, by passes of the
  // 5x5 binomial; orientation and descriptors read the level itself. 0: none (every mode but
  // quality). Blur in one image of a pair moves FAST's corners and scores; smoothing both measures
  // them on alike pixels (docs/evaluation.md, "Hard families").
  double detection_smoothing = 0;
  // Scale selection (core/detection/scale_selection.hpp): off in every mode (measured worse,
  // docs/evaluation.md "Scale selection").
  ScaleSelection scale_selection = ScaleSelection::off;
  KernelSet kernels = KernelSet::auto_select;  // pixel kernels; output does not depend on it
  int threads = 0;  // worker threads, 0 = TBB's default; output does not depend on it
  // Largest image accepted, in pixels: refuses absurd inputs before allocating. 2^26 pixels
  // (67 Mpx) holds an 8K frame (7680 x 4320 = 33 Mpx) with room to spare. The pyramid's pixels
  // over its levels are bounded at 6 x this (every mode's own pyramid is within 5.6 image areas).
  long long max_image_pixels = 1LL << 26;

  // Throws aief::Error naming the first invalid field and its value.
  void validate() const;
};

// The options of a named mode, starting from `base` (which keeps sizes, thresholds, kernels).
ExtractorOptions options_for_mode(Mode mode, ExtractorOptions base = {});

// Names used by the CLI and the output files. parse_* throw aief::Error on an unknown name.
std::string_view to_string(Distribution value);
std::string_view to_string(EntropyMeasure value);
std::string_view to_string(KernelSet value);
std::string_view to_string(Mode value);
std::string_view to_string(CoordinateMap value);
std::string_view to_string(StarvationGuard value);
std::string_view to_string(CandidateRanking value);
std::string_view to_string(PyramidResampling value);
std::string_view to_string(DetectionCells value);
std::string_view to_string(QuadtreeTies value);
std::string_view to_string(Orientation value);
std::string_view to_string(QuadtreeWeight value);
std::string_view to_string(FastThresholdFrom value);
std::string_view to_string(DescriptorKind value);
std::string_view to_string(ScaleSelection value);
Distribution parse_distribution(std::string_view name);
EntropyMeasure parse_entropy_measure(std::string_view name);
KernelSet parse_kernel_set(std::string_view name);
Mode parse_mode(std::string_view name);
CoordinateMap parse_coordinate_map(std::string_view name);
StarvationGuard parse_starvation_guard(std::string_view name);
CandidateRanking parse_candidate_ranking(std::string_view name);
DescriptorKind parse_descriptor_kind(std::string_view name);
// A candidate pool factor P: a number >= 1, or "inf" / "off" for no pool.
double parse_candidate_pool(std::string_view text);

// Fixed geometry of ORB (ORB-SLAM2 defaults, docs/design.md §7).
constexpr int kPatchSize = 31;    // rBRIEF patch side
constexpr int kPatchRadius = 15;  // half patch: orientation disc radius
constexpr int kEdgeBorder = 19;   // keypoints lie at least this far from a level's edge
constexpr int kDescriptorBytes = 32;
// Upper bound of max_image_pixels (2^26, the default): the entropy sums in Q32 fixed point
// (core/entropy/block_entropy.cpp, c log2 c * 2^32 per bin) stay exact below it for both measures.
constexpr long long kLargestMaxImagePixels = 1LL << 26;

}  // namespace aief

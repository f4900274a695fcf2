#pragma once
// Options of the extractor. Defaults are DESIGN.md section 1 (ORB-SLAM2's settings); no other
// file repeats them: the CLI, the JSON writer and the tests read them from these structs.
#include <string>
#include <string_view>

namespace aief {

// How the keypoints of a level are spread over its blocks (DESIGN.md section 1).
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

// Instruction set of the pixel kernels. Every set gives the same bytes (DESIGN.md section 5).
enum class KernelSet {
  auto_select,  // the best the CPU supports
  scalar,       // the reference in core/
  sse4_2,
  avx2,
  avx512bw,
  neon64,  // AArch64 Advanced SIMD
};

// Named presets over ExtractorOptions, the rows of the paper's tables.
enum class Mode {
  aief,              // proportional distribution + entropy mask at entropy_threshold
  orbslam2,          // quadtree, no entropy
  quadtree_entropy,  // quadtree + entropy mask
};

struct ExtractorOptions {
  int n_features = 1000;         // keypoints wanted over all levels (ORB-SLAM2 nFeatures)
  double scale_factor = 1.2;     // size ratio between two pyramid levels (ORB-SLAM2 scaleFactor)
  int n_levels = 8;              // pyramid levels (ORB-SLAM2 nLevels)
  int fast_threshold = 20;       // FAST-9 threshold tried first in a block (ORB-SLAM2 iniThFAST)
  int fast_min_threshold = 7;    // retry threshold when a block has no corner (ORB-SLAM2 minThFAST)
  int block_size = 32;           // side of an entropy / distribution block, level pixels
  Distribution distribution = Distribution::proportional;
  EntropyMeasure entropy = EntropyMeasure::histogram;
  // F of Eq. 9: a block is kept when its entropy is > F. 4.0 bits keeps textured blocks and
  // drops sky, walls and saturated areas on the Oxford images; `adapt` chooses F per scene.
  double entropy_threshold = 4.0;
  // Pair-free automatic F (core/auto_threshold.hpp) instead of entropy_threshold: Otsu's split
  // of the frame's own block entropies. `aief extract --threshold auto`.
  bool auto_threshold = false;
  KernelSet kernels = KernelSet::auto_select;  // pixel kernels; output does not depend on it
  int threads = 0;  // worker threads, 0 = TBB's default; output does not depend on it
  // Largest image accepted, in pixels: refuses absurd inputs before allocating. 2^26 pixels
  // (67 Mpx) holds an 8K frame (7680 x 4320 = 33 Mpx) with room to spare.
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
Distribution parse_distribution(std::string_view name);
EntropyMeasure parse_entropy_measure(std::string_view name);
KernelSet parse_kernel_set(std::string_view name);
Mode parse_mode(std::string_view name);

// Fixed geometry of ORB (ORB-SLAM2 defaults, DESIGN.md section 1).
constexpr int kPatchSize = 31;     // rBRIEF patch side
constexpr int kPatchRadius = 15;   // half patch: orientation disc radius
constexpr int kEdgeBorder = 19;    // keypoints lie at least this far from a level's edge
constexpr int kDescriptorBytes = 32;

}  // namespace aief

#include "aief/options.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "aief/error.hpp"

namespace aief {

namespace {

template <class T>
std::string str(T value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void require(bool ok, const std::string& message) {
  if (!ok) throw Error(message);
}

void require_int_range(const char* name, int value, int lo, int hi) {
  require(value >= lo && value <= hi, std::string(name) + " must be in [" + str(lo) + ", " +
                                          str(hi) + "], got " + str(value));
}

}  // namespace

void ExtractorOptions::validate() const {
  require_int_range("n_features", n_features, 1, 1'000'000);
  // The pyramid computes in float (ORB-SLAM2's arithmetic, core/level_geometry.cpp): check the
  // value it will use, so 1.00000001 (1.0 as a float, which makes every level budget 0/0) is
  // refused rather than accepted and silently rounded.
  const float scale_used = static_cast<float>(scale_factor);
  require(std::isfinite(scale_factor) && scale_used > 1.0f && scale_used <= 4.0f,
          "scale_factor must be > 1 and <= 4 in single precision (the pyramid computes in float), got " +
              str(scale_factor) + (std::isfinite(scale_factor) && scale_used == 1.0f ? ", which is 1 as a float" : ""));
  require_int_range("n_levels", n_levels, 1, 32);
  require_int_range("fast_threshold", fast_threshold, 1, 254);
  require_int_range("fast_min_threshold", fast_min_threshold, 1, fast_threshold);
  require_int_range("block_size", block_size, 8, 1024);
  require(distribution == Distribution::proportional || distribution == Distribution::quadtree,
          "distribution has an unknown value " + str(static_cast<int>(distribution)));
  require(entropy == EntropyMeasure::off || entropy == EntropyMeasure::histogram ||
              entropy == EntropyMeasure::intensity,
          "entropy has an unknown value " + str(static_cast<int>(entropy)));
  require(std::isfinite(entropy_threshold) && entropy_threshold >= 0.0 && entropy_threshold <= 64.0,
          "entropy_threshold must be in [0, 64] bits, got " + str(entropy_threshold));
  require(static_cast<int>(kernels) >= 0 && static_cast<int>(kernels) <= static_cast<int>(KernelSet::neon64),
          "kernels has an unknown value " + str(static_cast<int>(kernels)));
  require(coordinates == CoordinateMap::scaled || coordinates == CoordinateMap::pixel_centre,
          "coordinates has an unknown value " + str(static_cast<int>(coordinates)));
  require(!std::isnan(candidate_pool) && candidate_pool >= 1.0,
          "candidate_pool must be >= 1 (or infinity: no pool), got " + str(candidate_pool));
  require(starvation_guard == StarvationGuard::frame || starvation_guard == StarvationGuard::level,
          "starvation_guard has an unknown value " + str(static_cast<int>(starvation_guard)));
  require(candidate_ranking == CandidateRanking::peak_score || candidate_ranking == CandidateRanking::cross_score,
          "candidate_ranking has an unknown value " + str(static_cast<int>(candidate_ranking)));
  require_int_range("threads", threads, 0, 256);
  require(max_image_pixels >= 1 && max_image_pixels <= kLargestMaxImagePixels,
          "max_image_pixels must be in [1, " + str(kLargestMaxImagePixels) +
              "] (2^26: larger images would overflow the exact entropy sums), got " + str(max_image_pixels));
}

ExtractorOptions options_for_mode(Mode mode, ExtractorOptions base) {
  const EntropyMeasure measure =
      base.entropy == EntropyMeasure::off ? EntropyMeasure::histogram : base.entropy;
  const ExtractorOptions defaults;
  // Every mode but aief keeps the conventions of the code it reproduces (docs/design.md §11).
  base.coordinates = CoordinateMap::scaled;
  base.subpixel = false;
  base.candidate_pool = std::numeric_limits<double>::infinity();
  base.starvation_guard = StarvationGuard::frame;
  base.auto_skips_uniform_blocks = false;
  base.candidate_ranking = CandidateRanking::peak_score;
  base.auto_requires_two_classes = false;
  switch (mode) {
    case Mode::aief:
      base.distribution = Distribution::proportional;
      base.entropy = measure;
      base.coordinates = defaults.coordinates;
      base.subpixel = defaults.subpixel;
      base.candidate_pool = defaults.candidate_pool;
      base.starvation_guard = defaults.starvation_guard;
      base.auto_skips_uniform_blocks = defaults.auto_skips_uniform_blocks;
      base.candidate_ranking = defaults.candidate_ranking;
      base.auto_requires_two_classes = defaults.auto_requires_two_classes;
      break;
    case Mode::aief_paper:
      base.distribution = Distribution::proportional;
      base.entropy = measure;
      break;
    case Mode::orbslam2:
      base.distribution = Distribution::quadtree;
      base.entropy = EntropyMeasure::off;
      break;
    case Mode::quadtree_entropy:
      base.distribution = Distribution::quadtree;
      base.entropy = measure;
      break;
  }
  return base;
}

std::string_view to_string(Distribution value) {
  return value == Distribution::quadtree ? "quadtree" : "proportional";
}

std::string_view to_string(EntropyMeasure value) {
  switch (value) {
    case EntropyMeasure::off: return "off";
    case EntropyMeasure::histogram: return "histogram";
    case EntropyMeasure::intensity: return "intensity";
  }
  return "?";
}

std::string_view to_string(KernelSet value) {
  switch (value) {
    case KernelSet::auto_select: return "auto";
    case KernelSet::scalar: return "scalar";
    case KernelSet::sse4_2: return "sse4.2";
    case KernelSet::avx2: return "avx2";
    case KernelSet::avx512bw: return "avx512";
    case KernelSet::neon64: return "neon64";
  }
  return "?";
}

std::string_view to_string(Mode value) {
  switch (value) {
    case Mode::aief: return "aief";
    case Mode::aief_paper: return "aief-paper";
    case Mode::orbslam2: return "orbslam2";
    case Mode::quadtree_entropy: return "quadtree-entropy";
  }
  return "?";
}

Distribution parse_distribution(std::string_view name) {
  if (name == "proportional") return Distribution::proportional;
  if (name == "quadtree") return Distribution::quadtree;
  throw Error("unknown distribution '" + std::string(name) + "' (expected proportional or quadtree)");
}

EntropyMeasure parse_entropy_measure(std::string_view name) {
  if (name == "off") return EntropyMeasure::off;
  if (name == "histogram") return EntropyMeasure::histogram;
  if (name == "intensity") return EntropyMeasure::intensity;
  throw Error("unknown entropy measure '" + std::string(name) +
              "' (expected histogram, intensity or off)");
}

KernelSet parse_kernel_set(std::string_view name) {
  if (name == "auto") return KernelSet::auto_select;
  if (name == "scalar") return KernelSet::scalar;
  if (name == "sse4.2" || name == "sse4_2") return KernelSet::sse4_2;
  if (name == "avx2") return KernelSet::avx2;
  if (name == "avx512" || name == "avx512bw") return KernelSet::avx512bw;
  if (name == "neon64") return KernelSet::neon64;
  throw Error("unknown kernel set '" + std::string(name) +
              "' (expected auto, scalar, sse4.2, avx2, avx512 or neon64)");
}

Mode parse_mode(std::string_view name) {
  if (name == "aief") return Mode::aief;
  if (name == "aief-paper" || name == "aief_paper") return Mode::aief_paper;
  if (name == "orbslam2") return Mode::orbslam2;
  if (name == "quadtree-entropy" || name == "quadtree_entropy") return Mode::quadtree_entropy;
  throw Error("unknown mode '" + std::string(name) +
              "' (expected aief, aief-paper, orbslam2 or quadtree-entropy)");
}

std::string_view to_string(CoordinateMap value) {
  return value == CoordinateMap::scaled ? "scaled" : "pixel-centre";
}

std::string_view to_string(StarvationGuard value) {
  return value == StarvationGuard::frame ? "frame" : "level";
}

std::string_view to_string(CandidateRanking value) {
  return value == CandidateRanking::peak_score ? "peak" : "cross";
}

CandidateRanking parse_candidate_ranking(std::string_view name) {
  if (name == "cross") return CandidateRanking::cross_score;
  if (name == "peak") return CandidateRanking::peak_score;
  throw Error("unknown candidate ranking '" + std::string(name) + "' (expected cross or peak)");
}

CoordinateMap parse_coordinate_map(std::string_view name) {
  if (name == "scaled") return CoordinateMap::scaled;
  if (name == "pixel-centre" || name == "pixel_centre") return CoordinateMap::pixel_centre;
  throw Error("unknown coordinate map '" + std::string(name) + "' (expected pixel-centre or scaled)");
}

StarvationGuard parse_starvation_guard(std::string_view name) {
  if (name == "level") return StarvationGuard::level;
  if (name == "frame") return StarvationGuard::frame;
  throw Error("unknown starvation guard '" + std::string(name) + "' (expected level or frame)");
}

double parse_candidate_pool(std::string_view text) {
  if (text == "inf" || text == "off") return std::numeric_limits<double>::infinity();
  const std::string copy(text);
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(copy, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != copy.size() || !std::isfinite(value) || value < 1.0)
    throw Error("candidate pool must be a number >= 1 or inf, got '" + copy + "'");
  return value;
}

}  // namespace aief

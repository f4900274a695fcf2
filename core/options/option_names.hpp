#pragma once
// One name table per option enum. A value's name is what the CLI, the Python module, settings
// files and the output files' option records use; its C++ enumerator's name is accepted too, so
// "pixel_centre" reads as "pixel-centre" and "avx512bw" as "avx512" (the one alias rule).
// to_string / parse_* of aief/options.hpp and the option table (core/options/option_table.hpp) read
// these tables and nothing else: to add a value, add a row here.
#include <string>
#include <string_view>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"

namespace aief::option_names {

template <class Enum>
struct Name {
  Enum value;
  std::string_view name;        // written and read
  std::string_view enumerator;  // read too
};

// Specialised per enum: `what` names the kind in messages ("unknown mode 'orb'"), `names` lists
// every value in the order --help shows them.
template <class Enum>
struct Table;

// One enum's table: the kind, then each value as AIEF_NAME(enumerator, "name"), in --help's order.
// The enumerator is written once: its C++ spelling is the row's `enumerator` too.
#define AIEF_NAME(enumerator, written) \
  Name<E> { E::enumerator, written, #enumerator }
#define AIEF_NAME_TABLE(Enum, kind, ...)                 \
  template <>                                            \
  struct Table<Enum> {                                   \
    using E = Enum;                                      \
    static constexpr std::string_view what = kind;       \
    static constexpr Name<Enum> names[] = {__VA_ARGS__}; \
  };

AIEF_NAME_TABLE(Mode, "mode", AIEF_NAME(aief, "aief"), AIEF_NAME(aief_paper, "aief-paper"),
                AIEF_NAME(orbslam2, "orbslam2"), AIEF_NAME(quadtree_entropy, "quadtree-entropy"),
                AIEF_NAME(faithful, "faithful"), AIEF_NAME(quality, "quality"))

AIEF_NAME_TABLE(Distribution, "distribution", AIEF_NAME(proportional, "proportional"),
                AIEF_NAME(quadtree, "quadtree"))

AIEF_NAME_TABLE(EntropyMeasure, "entropy measure", AIEF_NAME(histogram, "histogram"),
                AIEF_NAME(intensity, "intensity"), AIEF_NAME(off, "off"))

AIEF_NAME_TABLE(KernelSet, "kernel set", AIEF_NAME(auto_select, "auto"),
                AIEF_NAME(scalar, "scalar"), AIEF_NAME(sse4_2, "sse4.2"), AIEF_NAME(avx2, "avx2"),
                AIEF_NAME(avx512bw, "avx512"), AIEF_NAME(neon64, "neon64"))

AIEF_NAME_TABLE(CoordinateMap, "coordinate map", AIEF_NAME(pixel_centre, "pixel-centre"),
                AIEF_NAME(scaled, "scaled"))

AIEF_NAME_TABLE(StarvationGuard, "starvation guard", AIEF_NAME(level, "level"),
                AIEF_NAME(frame, "frame"))

AIEF_NAME_TABLE(CandidateRanking, "candidate ranking", AIEF_NAME(cross_score, "cross"),
                AIEF_NAME(peak_score, "peak"))

AIEF_NAME_TABLE(MatcherKind, "matcher", AIEF_NAME(mutual, "mutual"), AIEF_NAME(ratio, "ratio"),
                AIEF_NAME(paper, "paper"), AIEF_NAME(mutual_ratio, "mutual_ratio"),
                AIEF_NAME(guided, "guided"))

AIEF_NAME_TABLE(PyramidResampling, "pyramid resampling", AIEF_NAME(q8, "q8"),
                AIEF_NAME(opencv, "opencv"))

AIEF_NAME_TABLE(DetectionCells, "detection cells", AIEF_NAME(blocks, "blocks"),
                AIEF_NAME(orbslam, "orbslam"))

AIEF_NAME_TABLE(Orientation, "orientation", AIEF_NAME(atan2, "atan2"),
                AIEF_NAME(opencv_fast, "fast-atan2"))

AIEF_NAME_TABLE(QuadtreeTies, "quadtree ties", AIEF_NAME(full, "full"),
                AIEF_NAME(orbslam, "orbslam"))

AIEF_NAME_TABLE(QuadtreeWeight, "quadtree weight", AIEF_NAME(none, "none"),
                AIEF_NAME(entropy, "entropy"))

AIEF_NAME_TABLE(FastThresholdFrom, "FAST threshold source", AIEF_NAME(none, "none"),
                AIEF_NAME(entropy, "entropy"))

AIEF_NAME_TABLE(DescriptorKind, "descriptor", AIEF_NAME(rbrief, "rbrief"), AIEF_NAME(box, "box"))

AIEF_NAME_TABLE(ScaleSelection, "scale selection", AIEF_NAME(off, "off"),
                AIEF_NAME(extrema, "extrema"))

#undef AIEF_NAME_TABLE
#undef AIEF_NAME

// The name of `value`; "?" for a value outside the table (an invalid cast).
template <class Enum>
std::string_view name_of(Enum value) {
  for (const Name<Enum>& n : Table<Enum>::names)
    if (n.value == value) return n.name;
  return "?";
}

// The row whose name or enumerator is `text`, or null.
template <class Enum>
const Name<Enum>* find(std::string_view text) {
  for (const Name<Enum>& n : Table<Enum>::names)
    if (n.name == text || n.enumerator == text) return &n;
  return nullptr;
}

// "a, b or c": the names, for messages and --help.
template <class Enum>
std::string expected_names(std::string_view last_separator = " or ") {
  std::string out;
  constexpr std::size_t count = std::size(Table<Enum>::names);
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) out += i + 1 == count ? last_separator : std::string_view(", ");
    out += Table<Enum>::names[i].name;
  }
  return out;
}

// Throws aief::Error "unknown mode 'orb' (expected aief, aief-paper, orbslam2 or
// quadtree-entropy)".
template <class Enum>
Enum parse(std::string_view text) {
  if (const Name<Enum>* n = find<Enum>(text)) return n->value;
  throw Error("unknown " + std::string(Table<Enum>::what) + " '" + std::string(text) +
              "' (expected " + expected_names<Enum>() + ")");
}

}  // namespace aief::option_names

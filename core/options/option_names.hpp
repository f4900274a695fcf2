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

template <>
struct Table<Mode> {
  static constexpr std::string_view what = "mode";
  static constexpr Name<Mode> names[] = {
      {Mode::aief, "aief", "aief"},
      {Mode::aief_paper, "aief-paper", "aief_paper"},
      {Mode::orbslam2, "orbslam2", "orbslam2"},
      {Mode::quadtree_entropy, "quadtree-entropy", "quadtree_entropy"},
      {Mode::faithful, "faithful", "faithful"},
      {Mode::quality, "quality", "quality"}};
};

template <>
struct Table<Distribution> {
  static constexpr std::string_view what = "distribution";
  static constexpr Name<Distribution> names[] = {
      {Distribution::proportional, "proportional", "proportional"},
      {Distribution::quadtree, "quadtree", "quadtree"}};
};

template <>
struct Table<EntropyMeasure> {
  static constexpr std::string_view what = "entropy measure";
  static constexpr Name<EntropyMeasure> names[] = {
      {EntropyMeasure::histogram, "histogram", "histogram"},
      {EntropyMeasure::intensity, "intensity", "intensity"},
      {EntropyMeasure::off, "off", "off"}};
};

template <>
struct Table<KernelSet> {
  static constexpr std::string_view what = "kernel set";
  static constexpr Name<KernelSet> names[] = {
      {KernelSet::auto_select, "auto", "auto_select"}, {KernelSet::scalar, "scalar", "scalar"},
      {KernelSet::sse4_2, "sse4.2", "sse4_2"},         {KernelSet::avx2, "avx2", "avx2"},
      {KernelSet::avx512bw, "avx512", "avx512bw"},     {KernelSet::neon64, "neon64", "neon64"}};
};

template <>
struct Table<CoordinateMap> {
  static constexpr std::string_view what = "coordinate map";
  static constexpr Name<CoordinateMap> names[] = {
      {CoordinateMap::pixel_centre, "pixel-centre", "pixel_centre"},
      {CoordinateMap::scaled, "scaled", "scaled"}};
};

template <>
struct Table<StarvationGuard> {
  static constexpr std::string_view what = "starvation guard";
  static constexpr Name<StarvationGuard> names[] = {{StarvationGuard::level, "level", "level"},
                                                    {StarvationGuard::frame, "frame", "frame"}};
};

template <>
struct Table<CandidateRanking> {
  static constexpr std::string_view what = "candidate ranking";
  static constexpr Name<CandidateRanking> names[] = {
      {CandidateRanking::cross_score, "cross", "cross_score"},
      {CandidateRanking::peak_score, "peak", "peak_score"}};
};

template <>
struct Table<MatcherKind> {
  static constexpr std::string_view what = "matcher";
  static constexpr Name<MatcherKind> names[] = {{MatcherKind::mutual, "mutual", "mutual"},
                                                {MatcherKind::ratio, "ratio", "ratio"},
                                                {MatcherKind::paper, "paper", "paper"}};
};

template <>
struct Table<PyramidResampling> {
  static constexpr std::string_view what = "pyramid resampling";
  static constexpr Name<PyramidResampling> names[] = {
      {PyramidResampling::q8, "q8", "q8"}, {PyramidResampling::opencv, "opencv", "opencv"}};
};

template <>
struct Table<DetectionCells> {
  static constexpr std::string_view what = "detection cells";
  static constexpr Name<DetectionCells> names[] = {{DetectionCells::blocks, "blocks", "blocks"},
                                                   {DetectionCells::orbslam, "orbslam", "orbslam"}};
};

template <>
struct Table<Orientation> {
  static constexpr std::string_view what = "orientation";
  static constexpr Name<Orientation> names[] = {
      {Orientation::atan2, "atan2", "atan2"},
      {Orientation::opencv_fast, "fast-atan2", "opencv_fast"}};
};

template <>
struct Table<QuadtreeTies> {
  static constexpr std::string_view what = "quadtree ties";
  static constexpr Name<QuadtreeTies> names[] = {{QuadtreeTies::full, "full", "full"},
                                                 {QuadtreeTies::orbslam, "orbslam", "orbslam"}};
};

template <>
struct Table<QuadtreeWeight> {
  static constexpr std::string_view what = "quadtree weight";
  static constexpr Name<QuadtreeWeight> names[] = {{QuadtreeWeight::none, "none", "none"},
                                                   {QuadtreeWeight::entropy, "entropy", "entropy"}};
};

template <>
struct Table<FastThresholdFrom> {
  static constexpr std::string_view what = "FAST threshold source";
  static constexpr Name<FastThresholdFrom> names[] = {
      {FastThresholdFrom::none, "none", "none"},
      {FastThresholdFrom::entropy, "entropy", "entropy"}};
};

template <>
struct Table<DescriptorKind> {
  static constexpr std::string_view what = "descriptor";
  static constexpr Name<DescriptorKind> names[] = {{DescriptorKind::rbrief, "rbrief", "rbrief"},
                                                   {DescriptorKind::box, "box", "box"}};
};

template <>
struct Table<ScaleSelection> {
  static constexpr std::string_view what = "scale selection";
  static constexpr Name<ScaleSelection> names[] = {{ScaleSelection::off, "off", "off"},
                                                   {ScaleSelection::extrema, "extrema", "extrema"}};
};

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

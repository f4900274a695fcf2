// The option tables of matching (MatchOptions), the adaptive sweep (SweepOptions) and RANSAC
// (RansacOptions), one row per option in record order (core/options/option_table.hpp), and their
// validate(), made from the rows. Adding one: CONTRIBUTING.md, "Adding an option". The CLI's
// flags of aief match and aief adapt, the keywords of aief.match, aief.adapt and
// aief.find_homography, and the record of a matches file come from here.
#include <iterator>
#include <limits>
#include <vector>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "core/options/malformed_row.hpp"
#include "core/options/option_access.hpp"
#include "core/options/option_table.hpp"
#include "core/options/sweepable_matcher.hpp"

namespace aief::option_table {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The rows of each struct, each table with its struct as O (AIEF_OPTION_ROW's).
template <class Options>
struct Rows;

template <>
struct Rows<MatchOptions> {
  using O = MatchOptions;
  static constexpr Row<O> list[] = {
      {AIEF_OPTION_ROW(kind), .cli_flag = "--matcher", .cli_value = "K",
       .python_keyword = "matcher", .python_position = 1,
       .help = "which nearest neighbours are matches: "
               "mutual = nearest both ways, ratio = Lowe's ratio test, "
               "paper = distance <= max(2 x the smallest, 30), "
               "mutual_ratio = mutual and the ratio test from the first set, "
               "guided = mutual_ratio's matches give the two views' epipolar geometry, then "
               "mutual and the ratio test within --epipolar-band of each line (for SfM)"},
      {AIEF_OPTION_ROW(ratio), .cli_flag = "--ratio", .cli_value = "R", .python_keyword = "ratio",
       .python_position = 2,
       .help = "Lowe's ratio test (matcher ratio, mutual_ratio, guided): a match is kept when "
               "its distance < this x the second nearest's",
       .low = 0, .high = 1, .low_is_open = true, .applies_with_key = "kind",
       .applies_with_value = "ratio|mutual_ratio|guided"},
      {AIEF_OPTION_ROW(max_distance), .python_keyword = "max_distance", .python_position = 3,
       .help = "matches farther than this many bits are dropped (256: none)", .low = 0,
       .high = 256},
      {AIEF_OPTION_ROW(epipolar_band_px), .cli_flag = "--epipolar-band", .cli_value = "PX",
       .python_keyword = "epipolar_band", .python_position = 4,
       .help = "matcher guided: a keypoint's candidates lie within this Sampson distance of its "
               "epipolar line, pixels",
       .low = 0, .high = 64, .low_is_open = true, .applies_with_key = "kind",
       .applies_with_value = "guided"},
  };
};
AIEF_CHECK_OPTION_ROWS(Rows<MatchOptions>::list);

template <>
struct Rows<SweepOptions> {
  using O = SweepOptions;
  static constexpr Row<O> list[] = {
      {AIEF_OPTION_ROW(first_threshold), .python_keyword = "first_threshold", .python_position = 1,
       .help = "F_0, the first threshold swept, bits (docs/design.md section 10)", .low = 0,
       .high = kInfinity},
      {AIEF_OPTION_ROW(step), .cli_flag = "--step", .cli_value = "S", .python_keyword = "step",
       .python_position = 2, .help = "sweep step S_p in bits", .low = 0.01, .high = 8},
      {AIEF_OPTION_ROW(min_inliers), .cli_flag = "--min-inliers", .cli_value = "N",
       .python_keyword = "min_inliers", .python_position = 3,
       .help = "inliers a threshold needs to be chosen", .low = 4, .high = 1000000},
  };
};
AIEF_CHECK_OPTION_ROWS(Rows<SweepOptions>::list);

template <>
struct Rows<RansacOptions> {
  using O = RansacOptions;
  static constexpr Row<O> list[] = {
      {AIEF_OPTION_ROW(threshold_px), .python_keyword = "threshold_px", .python_position = 1,
       .help = "a match is an inlier when its reprojection error is at most this, pixels", .low = 0,
       .high = kInfinity, .low_is_open = true},
      {AIEF_OPTION_ROW(confidence), .python_keyword = "confidence", .python_position = 2,
       .help = "stop when an all-inlier sample has been drawn this surely", .low = 0, .high = 1,
       .low_is_open = true, .high_is_open = true},
      {AIEF_OPTION_ROW(max_iterations), .python_keyword = "max_iterations", .python_position = 3,
       .help = "samples drawn at most", .low = 1,
       .high = static_cast<double>(std::numeric_limits<int>::max())},
      // Seeds are read as signed 64-bit integers: [0, 2^63).
      {AIEF_OPTION_ROW(seed), .python_keyword = "seed", .python_position = 4,
       .help = "the sampler's seed: the same seed, the same answer", .low = 0, .high = kInfinity},
  };
};
AIEF_CHECK_OPTION_ROWS(Rows<RansacOptions>::list);

}  // namespace

template <class Options>
const std::vector<Row<Options>>& table_of() {
  static const std::vector<Row<Options>> table(std::begin(Rows<Options>::list),
                                               std::end(Rows<Options>::list));
  return table;
}

template <>
const std::vector<Row<MatchOptions>>& rows_of<MatchOptions>() {
  return table_of<MatchOptions>();
}
template <>
const std::vector<Row<SweepOptions>>& rows_of<SweepOptions>() {
  return table_of<SweepOptions>();
}
template <>
const std::vector<Row<RansacOptions>>& rows_of<RansacOptions>() {
  return table_of<RansacOptions>();
}

}  // namespace aief::option_table

namespace aief {

void MatchOptions::validate() const { option_table::check_fields(*this); }

void SweepOptions::validate() const {
  option_table::check_fields(*this);
  require_sweepable(match);
  ransac.validate();
}

void require_sweepable(const MatchOptions& options) {
  options.validate();
  if (options.kind == MatcherKind::guided)
    throw Error(
        "the sweep scores each threshold by its matches' homography: matcher guided "
        "(two views of a 3D scene, by their epipolar geometry) does not apply; use "
        "mutual, ratio, paper or mutual_ratio");
}

void RansacOptions::validate() const { option_table::check_fields(*this); }

}  // namespace aief

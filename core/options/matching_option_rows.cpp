// The option tables of matching (MatchOptions), the adaptive sweep (SweepOptions) and RANSAC
// (RansacOptions), and their validate(), made from the rows (core/options/option_table.hpp). The CLI's
// flags of aief match and aief adapt, the keywords of aief.match, aief.adapt and
// aief.find_homography, and the record of a matches file come from here.
#include <limits>

#include "aief/adapt.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "core/options/option_access.hpp"
#include "core/options/option_table.hpp"

namespace aief::option_table {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

template <>
const std::vector<Row<MatchOptions>>& rows_of<MatchOptions>() {
  using M = MatchOptions;
  static const std::vector<Row<M>> table = {
      {.key = "kind",
       .field = access<&M::kind>,
       .cli_flag = "--matcher",
       .cli_value = "K",
       .python_keyword = "matcher",
       .python_position = 1,
       .help = "which nearest neighbours are matches: mutual = nearest both ways, ratio = Lowe's "
               "ratio test, paper = distance <= max(2 x the smallest, 30)"},
      {.key = "ratio",
       .field = access<&M::ratio>,
       .cli_flag = "--ratio",
       .cli_value = "R",
       .python_keyword = "ratio",
       .python_position = 2,
       .help = "Lowe's ratio test: a match is kept when its distance < this x the second nearest's",
       .low = 0,
       .high = 1,
       .low_is_open = true,
       .applies_with_key = "kind",
       .applies_with_value = "ratio"},
      {.key = "max_distance",
       .field = access<&M::max_distance>,
       .python_keyword = "max_distance",
       .python_position = 3,
       .help = "matches farther than this many bits are dropped (256: none)",
       .low = 0,
       .high = 256},
  };
  return table;
}

template <>
const std::vector<Row<SweepOptions>>& rows_of<SweepOptions>() {
  using S = SweepOptions;
  static const std::vector<Row<S>> table = {
      {.key = "first_threshold",
       .field = access<&S::first_threshold>,
       .python_keyword = "first_threshold",
       .python_position = 1,
       .help = "F_0, the first threshold swept, bits (docs/design.md section 10)",
       .low = 0,
       .high = kInfinity},
      {.key = "step",
       .field = access<&S::step>,
       .cli_flag = "--step",
       .cli_value = "S",
       .python_keyword = "step",
       .python_position = 2,
       .help = "sweep step S_p in bits",
       .low = 0.01,
       .high = 8},
      {.key = "min_inliers",
       .field = access<&S::min_inliers>,
       .cli_flag = "--min-inliers",
       .cli_value = "N",
       .python_keyword = "min_inliers",
       .python_position = 3,
       .help = "inliers a threshold needs to be chosen",
       .low = 4,
       .high = 1'000'000},
  };
  return table;
}

template <>
const std::vector<Row<RansacOptions>>& rows_of<RansacOptions>() {
  using R = RansacOptions;
  static const std::vector<Row<R>> table = {
      {.key = "threshold_px",
       .field = access<&R::threshold_px>,
       .python_keyword = "threshold_px",
       .python_position = 1,
       .help = "a match is an inlier when its reprojection error is at most this, pixels",
       .low = 0,
       .high = kInfinity,
       .low_is_open = true},
      {.key = "confidence",
       .field = access<&R::confidence>,
       .python_keyword = "confidence",
       .python_position = 2,
       .help = "stop when an all-inlier sample has been drawn this surely",
       .low = 0,
       .high = 1,
       .low_is_open = true,
       .high_is_open = true},
      {.key = "max_iterations",
       .field = access<&R::max_iterations>,
       .python_keyword = "max_iterations",
       .python_position = 3,
       .help = "samples drawn at most",
       .low = 1,
       .high = std::numeric_limits<int>::max()},
      // Seeds are read as signed 64-bit integers: [0, 2^63).
      {.key = "seed",
       .field = access<&R::seed>,
       .python_keyword = "seed",
       .python_position = 4,
       .help = "the sampler's seed: the same seed, the same answer",
       .low = 0,
       .high = kInfinity},
  };
  return table;
}

}  // namespace aief::option_table

namespace aief {

void MatchOptions::validate() const { option_table::check_fields(*this); }

void SweepOptions::validate() const {
  option_table::check_fields(*this);
  match.validate();
  ransac.validate();
}

void RansacOptions::validate() const { option_table::check_fields(*this); }

}  // namespace aief

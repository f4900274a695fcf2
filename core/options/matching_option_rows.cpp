// The option tables of matching (MatchOptions), the adaptive sweep (SweepOptions) and RANSAC
// (RansacOptions), and their validate(), made from the rows (core/options/option_table.hpp): the
// data is core/options/matching_option_rows.json (made into C++ by
// cmake/generate_option_rows.cmake). The CLI's flags of aief match and aief adapt, the keywords of
// aief.match, aief.adapt and aief.find_homography, and the record of a matches file come from here.
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
  static const std::vector<Row<MatchOptions>> table = {
#include "MatchOptions_rows.inc"
  };
  return table;
}

template <>
const std::vector<Row<SweepOptions>>& rows_of<SweepOptions>() {
  static const std::vector<Row<SweepOptions>> table = {
#include "SweepOptions_rows.inc"
  };
  return table;
}

template <>
const std::vector<Row<RansacOptions>>& rows_of<RansacOptions>() {
  static const std::vector<Row<RansacOptions>> table = {
#include "RansacOptions_rows.inc"
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

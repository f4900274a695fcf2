#pragma once
// What makes an option table's rows malformed, checked as the rows compile: each table's file
// (core/options/extractor_option_rows.cpp, matching_option_rows.cpp) holds
// AIEF_CHECK_OPTION_ROWS(its rows), so a malformed row stops the build. tests/test_option_rows.cpp
// shows each kind of bad row found, and the CTests malformed_option_row_* that a bad row fails to
// compile (tests/compile_fail/malformed_option_row.cpp).
#include <array>
#include <iterator>
#include <string_view>
#include <type_traits>

#include "aief/options.hpp"
#include "core/options/option_table.hpp"

namespace aief::option_table {

// The first malformed row of a table: its key (or its place's neighbour's, for a row without a
// key) and what is wrong. Empty `problem`: the table is well formed.
struct RowProblem {
  std::string_view key = {};
  std::string_view problem = {};
  constexpr bool empty() const { return problem.empty(); }
};

namespace row_checks {

constexpr bool has_newline(std::string_view text) {
  return text.find('\n') != std::string_view::npos || text.find('\r') != std::string_view::npos;
}

// Whether `name` (non-empty) is a name of another row than `self` among `names_of(row)`.
template <class Rows, class Names>
constexpr bool taken_by_another(const Rows& rows, const void* self, std::string_view name,
                                Names names_of) {
  if (name.empty()) return false;
  for (const auto& other : rows) {
    if (static_cast<const void*>(&other) == self) continue;
    for (std::string_view taken : names_of(other))
      if (taken == name) return true;
  }
  return false;
}

template <class Row>
constexpr std::array<std::string_view, 2> flags_of(const Row& row) {
  return {row.cli_flag, row.old_cli_flag};
}
template <class Row>
constexpr std::array<std::string_view, 2> keywords_of(const Row& row) {
  return {row.python_keyword, row.old_python_keyword};
}
template <class Row>
constexpr std::array<std::string_view, 2> settings_keys_of(const Row& row) {
  return {row.yaml_key, row.old_yaml_key};
}

template <class Row>
constexpr std::string_view problem_of_its_own(const Row& row) {
  if (row.key.empty()) return "a row without a key";
  if (row.help.empty()) return "no help";
  for (std::string_view text : {row.help, row.cli_value, row.words, row.needs_mask, row.acts_with})
    if (has_newline(text)) return "a newline in its help or another text (--help is one line)";
  if (row.low > row.high) return "low > high";
  if (!row.cli_flag.empty() && !row.cli_flag.starts_with("--")) return "a CLI flag without --";
  if (!row.old_cli_flag.empty() && !row.old_cli_flag.starts_with("--"))
    return "an earlier CLI flag without --";
  if (row.python_position < 0) return "a negative python_position";
  for (std::string_view value : row.per_mode.all())
    if (value == kModeValueMissing)
      return "per_mode without a value for every mode (\"\" leaves the option as it was)";
  return {};
}

}  // namespace row_checks

// The first malformed row of `rows` (an array or vector of Row<Options>): a row without a key or
// help; a key, CLI flag, Python keyword or position, or settings key that is another row's (the
// earlier spellings included); low > high; a newline in a text --help prints; a per_mode that
// leaves a mode out (a row that names per_mode gives every mode its value); per_mode in a table
// without modes (only ExtractorOptions has them).
template <class Rows>
constexpr RowProblem malformed_row(const Rows& rows) {
  using Row = std::remove_cvref_t<decltype(*std::begin(rows))>;
  constexpr bool has_modes = std::is_same_v<Row, OptionRow>;
  for (const Row& row : rows) {
    const RowProblem own{row.key, row_checks::problem_of_its_own(row)};
    if (!own.empty()) return own;
    if (!has_modes && row.per_mode.any()) return {row.key, "per_mode in a table without modes"};
    auto keys = [](const Row& r) { return std::array<std::string_view, 1>{r.key}; };
    if (row_checks::taken_by_another(rows, &row, row.key, keys)) return {row.key, "a second row"};
    for (std::string_view flag : row_checks::flags_of(row))
      if (row_checks::taken_by_another(rows, &row, flag, row_checks::flags_of<Row>))
        return {row.key, "a CLI flag another row has"};
    for (std::string_view keyword : row_checks::keywords_of(row))
      if (row_checks::taken_by_another(rows, &row, keyword, row_checks::keywords_of<Row>))
        return {row.key, "a Python keyword another row has"};
    for (std::string_view key : row_checks::settings_keys_of(row))
      if (row_checks::taken_by_another(rows, &row, key, row_checks::settings_keys_of<Row>))
        return {row.key, "a settings key another row has"};
    for (const Row& other : rows)
      if (&other != &row && row.python_position > 0 && other.python_position == row.python_position)
        return {row.key, "a Python position another row has"};
  }
  return {};
}

}  // namespace aief::option_table

// Stops the build at a malformed row; the problem and the row's key are malformed_row(rows)'s (a
// test prints them: tests/test_option_rows.cpp).
#define AIEF_CHECK_OPTION_ROWS(rows)                               \
  static_assert(::aief::option_table::malformed_row(rows).empty(), \
                "a malformed option row (core/options/malformed_row.hpp)")

// ExtractorOptions' option rows (core/options/option_table.hpp): the data, one row per option, is
// core/options/extractor_option_rows.json (made into C++ by cmake/generate_option_rows.cmake); here
// are the few pieces of code its rows name (the mode's preset access, the setters of F and P). The
// value code that reads the rows (parsing, ranges, records, validate()) is in
// core/options/option_table.cpp.
#include <limits>
#include <string_view>
#include <vector>

#include "core/options/option_access.hpp"
#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"

namespace aief::option_table {

namespace {

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

// The table, from core/options/extractor_option_rows.json. Record order is this order.
std::vector<OptionRow> make_rows() {
  return {
#include "ExtractorOptions_rows.inc"
  };
}

}  // namespace

template <>
const std::vector<Row<ExtractorOptions>>& rows_of<ExtractorOptions>() {
  static const std::vector<OptionRow> table = make_rows();
  return table;
}

}  // namespace aief::option_table

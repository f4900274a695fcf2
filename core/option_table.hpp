#pragma once
// The option table: one row per extractor option, the only place an option is described. The
// CLI's flags, parser and --help (tools/cli_args.cpp), the Python module's keywords
// (python/bind_extractor.cpp), the ORB-SLAM drop-ins' settings keys
// (opencv/orbslam_extractor_base.cpp), ExtractorOptions::validate(), options_for_mode() and the
// option record of every output file (io/) are all made from it; tests/test_option_table.cpp
// checks that every option reaches every front end.
//
// How to add an option:
//   1. a field with its default and one comment in ExtractorOptions (include/aief/options.hpp);
//      an enum gets its name table in core/option_names.hpp;
//   2. one row in make_rows() (core/option_table.cpp): record key, CLI flag, Python keyword,
//   settings
//      key, help, kind and range, the value each mode sets, whether it changes the output.
// Nothing else: every front end, --help, validate() and the records pick the row up.
//
// Rules every front end shares (resolve_options): the mode sets its values first, the options
// given override them, and a given option the mode cannot honour is refused, naming both. Numbers
// are decimal (no hex, no "inf" unless the row names it), within the row's range.
#include <array>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "aief/options.hpp"

namespace aief::option_table {

enum class ValueKind {
  integer,  // decimal digits, optional sign
  number,   // decimal, optional fraction and exponent; or one of the row's words
  choice,   // a name of the row's enum (core/option_names.hpp)
  toggle,   // one of the row's two words ("on|off"): true, false
};

// A value as the table carries it: integer rows hold long long, number rows double (or the word
// given instead, e.g. "inf", "auto"), choice rows the canonical name, toggle rows bool.
using OptionValue = std::variant<bool, long long, double, std::string_view>;

// A choice row's names, type-erased from option_names::Table<Enum>.
struct ChoiceNames {
  std::string_view what;                      // "entropy measure"
  std::vector<std::string_view> names;        // in --help order
  std::vector<std::string_view> enumerators;  // accepted too
};

// How a row reads and writes its field; made from the field's type by access<&ExtractorOptions::x>
// (core/option_table.cpp): int -> integer, double -> number, bool -> toggle, enum -> choice.
struct FieldAccess {
  ValueKind kind = ValueKind::integer;
  OptionValue (*get)(const ExtractorOptions&) = nullptr;         // null for the mode (a preset)
  void (*set)(ExtractorOptions&, const OptionValue&) = nullptr;  // null for the mode
  const ChoiceNames* (*choices)() = nullptr;                     // choice rows

  constexpr FieldAccess with_set(void (*setter)(ExtractorOptions&, const OptionValue&)) const {
    FieldAccess copy = *this;
    copy.set = setter;
    return copy;
  }
};

struct OptionRow {
  std::string_view key = {};  // ExtractorOptions' field and the record key ("mode": the preset)
  FieldAccess field = {};
  std::string_view cli_flag = {};   // "--features"; empty: set through another row (record only)
  std::string_view cli_value = {};  // --help's placeholder: "N"
  std::string_view python_keyword = {};  // aief.Extractor(n_features=...)
  int python_position = 0;  // 1, 2, ...: positional order in aief.Extractor(...); 0: keyword only
  std::string_view yaml_key = {};  // the ORB-SLAM settings key
  std::string_view help = {};      // one line; --help adds the default
  double low = 0, high = 0;        // integer and number rows: the range [low, high]
  bool low_is_open = false;        // (low, high]
  std::string_view words =
      {};  // toggle: "on|off" (true first); number: words taken instead ("inf|off")
  // The value each mode sets, in Mode order (aief, aief-paper, orbslam2, quadtree-entropy,
  // faithful), as a front end would write it: "" leaves the option as it was, "default" takes
  // ExtractorOptions{}'s value, and a leading '=' marks the mode's definition: a different given
  // value is refused.
  std::array<std::string_view, 5> per_mode = {};
  bool changes_output = true;  // false: kernels, threads, limits (the bytes never depend on them)
  std::string_view needs_mask =
      {};  // non-empty: refused with the entropy mask off; says what it does

  ValueKind kind() const { return field.kind; }
  bool is_field() const { return field.get != nullptr; }
  bool has_front_ends() const { return !cli_flag.empty(); }
};

// Every row: the mode first, then the fields of ExtractorOptions in record order.
const std::vector<OptionRow>& rows();
const OptionRow& row(std::string_view key);  // throws aief::Error for an unknown key

// `text` as `row`'s value. Throws aief::Error naming the option as the user did (`named`:
// "--features", "n_features", "ORBextractor.nFeatures") and the accepted values.
OptionValue parse_value(const OptionRow& row, std::string_view text, std::string_view named);

// The one number syntax of every option and CLI number. Integers: decimal digits with an optional
// sign. Numbers: [+-] digits [. digits] [e [+-] digits] (or .5): decimal only, so "0x10", "inf",
// "nan" and " 1" are not numbers; an underflow reads as the tiny value it is (1e-320), an overflow
// fails, and -0 reads as 0. False when `text` is not one.
bool parse_integer(std::string_view text, long long& value);
bool parse_decimal(std::string_view text, double& value);

// An option a front end was given, as text.
struct GivenOption {
  const OptionRow* row;
  std::string text;   // as written; Python numbers as their shortest repr
  std::string named;  // as the front end names it
};

// The one resolution: the mode's values (aief unless given), then the given options, then
// validate(). Throws aief::Error for a bad value, a conflict with the mode, or an option that
// needs the entropy mask while it is off.
ExtractorOptions resolve_options(const std::vector<GivenOption>& given);

// The record of `options`: every field, in table order, as (key, value). A number row's value
// that is infinite is the word "inf".
std::vector<std::pair<std::string_view, OptionValue>> record_of(const ExtractorOptions& options);

// An option record read back from a file: (key, value as the file holds it: digits, a name or
// word, true / false), in any order.
using RecordedOptions = std::vector<std::pair<std::string, std::string>>;

// A field that changes the output and differs between two records; a field one record lacks is
// "not recorded" there.
struct OptionDifference {
  std::string key, before, after;
};

// The fields that change the output (rows with changes_output) whose values differ between
// `before` and `after`, in table order. Numbers compare as numbers (1.2 and 1.20 are the same),
// everything else as text. Empty: outputs made with either record are the same bytes. Batch
// resume redoes an output with differences; merge refuses shards with them (io/option_record.hpp).
std::vector<OptionDifference> output_differences(const RecordedOptions& before,
                                                 const RecordedOptions& after);

// "n_features 500 -> 3000".
std::string text_of(const OptionDifference& difference);

// A value as a front end would write it: 1000, 1.2, inf, pixel-centre, on.
std::string text_of(const OptionRow& row, const OptionValue& value);

// The row's accepted values for --help and messages: "an integer in [1, 1000000]",
// "aief, aief-paper, orbslam2 or quadtree-entropy", "on or off".
std::string expected_values(const OptionRow& row);

// "1000", or "pixel-centre; scaled in aief-paper, orbslam2, quadtree-entropy": --help's default.
std::string defaults_text(const OptionRow& row);

}  // namespace aief::option_table

#pragma once
// The option tables: one row per option of each options struct (ExtractorOptions, MatchOptions,
// SweepOptions, RansacOptions), the only place an option is described. The CLI's flags, parser
// and --help (tools/cli_args.cpp), the Python module's keywords and defaults
// (python/option_keywords.cpp), the ORB-SLAM drop-ins' settings keys
// (opencv/orbslam_extractor_base.cpp), validate(), options_for_mode() and the option record of
// every output file (io/option_record.hpp) are all made from them; tests/test_option_table.cpp
// checks that every option reaches every front end, python/tests/test_stub.py that the type stub
// says what the rows say.
//
// How to add an option, and which tests hold each place: CONTRIBUTING.md, "Adding an option".
// The rows are plain C++ (core/options/extractor_option_rows.cpp, matching_option_rows.cpp),
// checked as they compile (core/options/malformed_row.hpp).
//
// Rules every front end shares (resolve_options): the mode sets its values first, the options
// given override them, and a given option the mode cannot honour is refused, naming both. Numbers
// are decimal (no hex, no "inf" unless the row names it), within the row's range.
#include <array>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"

namespace aief::option_table {

enum class ValueKind {
  integer,  // decimal digits, optional sign
  number,   // decimal, optional fraction and exponent; or one of the row's words
  choice,   // a name of the row's enum (core/options/option_names.hpp)
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

// What a row's values are, whatever struct the row fills: what parsing, messages and the range
// check read (parse_value, expected_values, text_of).
struct ValueSpec {
  ValueKind kind = ValueKind::integer;
  const ChoiceNames* (*choices)() = nullptr;
  double low = 0, high = 0;
  bool low_is_open = false, high_is_open = false;
  std::string_view words = {};
};

// How a row reads and writes its field of `Options`; made from the field's type by
// access<&Options::x> (core/options/option_access.hpp): int -> integer, double -> number, bool ->
// toggle, enum -> choice.
template <class Options>
struct FieldAccess {
  ValueKind kind = ValueKind::integer;
  OptionValue (*get)(const Options&) = nullptr;         // null for the mode (a preset)
  void (*set)(Options&, const OptionValue&) = nullptr;  // null for the mode
  const ChoiceNames* (*choices)() = nullptr;            // choice rows

  constexpr FieldAccess with_set(void (*setter)(Options&, const OptionValue&)) const {
    FieldAccess copy = *this;
    copy.set = setter;
    return copy;
  }
};

// The word of a PerMode member a row left out: a malformed row (malformed_row).
inline constexpr std::string_view kModeValueMissing = "(no value given for this mode)";

// The value each mode sets (Row::per_mode), one member per Mode, as a front end would write it:
// "" leaves the option as it was, "default" (kDefault) takes ExtractorOptions{}'s value, and a
// leading '=' marks the mode's definition: a different given value is refused. A row that names
// per_mode names every mode.
struct PerMode {
  std::string_view aief = kModeValueMissing;
  std::string_view aief_paper = kModeValueMissing;
  std::string_view orbslam2 = kModeValueMissing;
  std::string_view quadtree_entropy = kModeValueMissing;
  std::string_view faithful = kModeValueMissing;
  std::string_view quality = kModeValueMissing;

  constexpr std::string_view operator[](Mode mode) const {
    switch (mode) {
      case Mode::aief: return aief;
      case Mode::aief_paper: return aief_paper;
      case Mode::orbslam2: return orbslam2;
      case Mode::quadtree_entropy: return quadtree_entropy;
      case Mode::faithful: return faithful;
      case Mode::quality: return quality;
    }
    return kModeValueMissing;
  }
  // Every member, in Mode order.
  constexpr std::array<std::string_view, 6> all() const {
    return {aief, aief_paper, orbslam2, quadtree_entropy, faithful, quality};
  }
  // Whether some mode sets the option.
  constexpr bool any() const {
    for (std::string_view value : all())
      if (!value.empty()) return true;
    return false;
  }
};

// A row without per_mode: no mode sets the option.
inline constexpr PerMode kNoModeSetsIt = {"", "", "", "", "", ""};

// One option of one options struct (ExtractorOptions, MatchOptions, SweepOptions, RansacOptions):
// the only place it is described. yaml_key, per_mode and needs_mask are the extractor's (its
// settings files, its modes, its entropy mask); applies_with_* the matcher's ratio rule; the
// other tables leave them empty.
template <class Options>
struct Row {
  std::string_view key = {};  // the field's name and the record key ("mode": the preset)
  FieldAccess<Options> field = {};
  std::string_view cli_flag = {};        // "--features"; empty: no flag
  std::string_view cli_value = {};       // --help's placeholder: "N"
  std::string_view python_keyword = {};  // aief.Extractor(n_features=...); empty: none
  int python_position = 0;  // 1, 2, ...: positional order in the Python call; 0: keyword only
  std::string_view yaml_key = {};  // the ORB-SLAM settings key
  // Earlier spellings, still accepted (CHANGELOG.md): the CLI flag, the Python keyword, the
  // settings key the option had before it took its record key's name; empty: none.
  std::string_view old_cli_flag = {}, old_python_keyword = {}, old_yaml_key = {};
  std::string_view help = {};  // one line; --help adds the default
  double low = 0, high = 0;    // integer and number rows: the range [low, high]
  bool low_is_open = false;    // (low, high]
  bool high_is_open = false;   // [low, high)
  std::string_view words =
      {};  // toggle: "on|off" (true first); number: words taken instead ("inf|off")
  PerMode per_mode = kNoModeSetsIt;  // the value each mode sets
  bool changes_output = true;  // false: kernels, threads, limits (the bytes never depend on them)
  std::string_view needs_mask = {};  // non-empty: refused with the entropy mask off when it changes
                                     // a value; says what it does
  // Non-empty: the row applies only while the row `applies_with_key` holds one of the values
  // `applies_with_value` lists, joined by '|' (--ratio with --matcher ratio|mutual_ratio); given
  // otherwise, it is refused.
  std::string_view applies_with_key = {}, applies_with_value = {};
  // The extractor's: the other fields this option needs to act, "key=value" joined by ','
  // (fast_threshold_from: "detection_cells=blocks"); without them it does nothing. Given a value
  // other than the one it holds, it is refused naming what it needs (resolve_options); a variant
  // neither the defaults nor any mode hold is refused by validate() (core/options/acts_with.hpp).
  std::string_view acts_with = {};
  // false: the adaptive sweep (aief adapt, match --adaptive) never reads it (it tries every F
  // itself, without the threshold fallback); given to the sweep, it is refused.
  bool read_by_sweep = true;

  constexpr ValueKind kind() const { return field.kind; }
  constexpr bool is_field() const { return field.get != nullptr; }
  constexpr bool has_front_ends() const { return !cli_flag.empty(); }
  constexpr ValueSpec spec() const {
    return {field.kind, field.choices, low, high, low_is_open, high_is_open, words};
  }
};

using OptionRow = Row<ExtractorOptions>;

// The per_mode word that takes ExtractorOptions{}'s value. The seven conventions every mode but
// aief keeps from the code it reproduces (x * scale, no sub-pixel, no pool, frame-wide guard,
// peak ranking, every block in the automatic F) are written with it.
inline constexpr std::string_view kDefault = "default";

// The rows of each options struct, in record order. ExtractorOptions' are in
// core/options/extractor_option_rows.cpp, the matcher's, sweep's and RANSAC's in
// core/options/matching_option_rows.cpp.
template <class Options>
const std::vector<Row<Options>>& rows_of();
template <>
const std::vector<Row<ExtractorOptions>>& rows_of<ExtractorOptions>();
template <>
const std::vector<Row<MatchOptions>>& rows_of<MatchOptions>();
template <>
const std::vector<Row<SweepOptions>>& rows_of<SweepOptions>();
template <>
const std::vector<Row<RansacOptions>>& rows_of<RansacOptions>();

// The row of `key`; throws aief::Error for an unknown key.
template <class Options>
const Row<Options>& row_of(std::string_view key) {
  for (const Row<Options>& r : rows_of<Options>())
    if (r.key == key) return r;
  throw Error("no option '" + std::string(key) + "'");
}

// The extractor's rows: the mode first, then the fields of ExtractorOptions in record order.
inline const std::vector<OptionRow>& rows() { return rows_of<ExtractorOptions>(); }
inline const OptionRow& row(std::string_view key) { return row_of<ExtractorOptions>(key); }

// `text` as a value of `spec`. Throws aief::Error naming the option as the user did (`named`:
// "--features", "n_features", "ORBextractor.nFeatures") and the accepted values.
OptionValue parse_value(const ValueSpec& spec, std::string_view text, std::string_view named);
template <class Options>
OptionValue parse_value(const Row<Options>& row, std::string_view text, std::string_view named) {
  return parse_value(row.spec(), text, named);
}

// The one number syntax of every option and CLI number. Integers: decimal digits with an optional
// sign. Numbers: [+-] digits [. digits] [e [+-] digits] (or .5): decimal only, so "0x10", "inf",
// "nan" and " 1" are not numbers; an underflow reads as the tiny value it is (1e-320), an overflow
// fails, and -0 reads as 0. False when `text` is not one.
bool parse_integer(std::string_view text, long long& value);
bool parse_decimal(std::string_view text, double& value);

// A value as a front end would write it: 1000, 1.2, inf, pixel-centre, on.
std::string text_of(const ValueSpec& spec, const OptionValue& value);
template <class Options>
std::string text_of(const Row<Options>& row, const OptionValue& value) {
  return text_of(row.spec(), value);
}

// The row's accepted values for --help and messages: "an integer in [1, 1000000]",
// "aief, aief-paper, orbslam2 or quadtree-entropy", "on or off".
std::string expected_values(const ValueSpec& spec);
template <class Options>
std::string expected_values(const Row<Options>& row) {
  return expected_values(row.spec());
}

// --help's default: "1000", or for the extractor "pixel-centre; scaled in aief-paper, orbslam2,
// quadtree-entropy" (the modes that set another value).
std::string defaults_text(const OptionRow& row);
template <class Options>
std::string defaults_text(const Row<Options>& row) {
  return text_of(row, row.field.get(Options{}));
}

// Throws aief::Error "key must be <expected values>, got <value>" when `value` is outside `spec`
// (NaN never is inside; infinity only where the row's words name "inf").
void check_value(std::string_view key, const ValueSpec& spec, const OptionValue& value);

// Every field of `options` within its row's range and names: the per-field half of validate().
template <class Options>
void check_fields(const Options& options) {
  for (const Row<Options>& r : rows_of<Options>())
    if (r.is_field()) check_value(r.key, r.spec(), r.field.get(options));
}

// How a front end names a row: the CLI by its flag, Python by its keyword.
enum class FrontEnd { cli, python };
template <class Options>
std::string name_in(const Row<Options>& row, FrontEnd front_end) {
  return std::string(front_end == FrontEnd::cli ? row.cli_flag : row.python_keyword);
}

// An option a front end was given, as text.
template <class Options>
struct Given {
  const Row<Options>* row;
  std::string text;   // as written; Python numbers as their shortest repr
  std::string named;  // as the front end names it
};
using GivenOption = Given<ExtractorOptions>;

// What the options are for: one extraction after another; the adaptive sweep over a pair (aief
// adapt, match --adaptive), which chooses F itself; or aief eval's rows, which turn the
// automatic F on per row (so the automatic F's options are taken without it).
enum class Use { extraction, sweep, evaluation };

// The extractor's resolution: the mode's values (aief unless given), then the given options in
// table order, then validate(). Throws aief::Error for a bad value, a conflict with the mode or
// between two given options (entropy_threshold 3 and auto_threshold on), an option that needs
// the entropy mask while it is off, or one that cannot act with the other options (acts_with) or
// in the sweep (read_by_sweep), when it would change a value. Without a
// given mode, a mode whose every value is given (Extractor(**extractor.options)) is the mode
// too: a value it sets is no request.
ExtractorOptions resolve_options(const std::vector<GivenOption>& given, Use use = Use::extraction);

// Whether `value` is one of `values`, words joined by '|' (a row's applies_with_value), and
// those words as a message says them ("ratio, mutual_ratio or guided").
bool is_one_of(std::string_view values, std::string_view value);
std::string one_of_text(std::string_view values);

// The same for a struct without modes (MatchOptions, SweepOptions, RansacOptions): `options` (the
// defaults unless given), the given options in table order, the applies_with rule, validate().
template <class Options>
Options resolve_options(const std::vector<Given<Options>>& given, FrontEnd front_end,
                        Options options = {}) {
  for (const Row<Options>& r : rows_of<Options>())
    for (const Given<Options>& g : given)
      if (g.row == &r) r.field.set(options, parse_value(r, g.text, g.named));
  for (const Given<Options>& g : given) {
    if (g.row->applies_with_key.empty()) continue;
    const Row<Options>& with = row_of<Options>(g.row->applies_with_key);
    const std::string holds = text_of(with, with.field.get(options));
    if (!is_one_of(g.row->applies_with_value, holds))
      throw Error(g.named + " applies to " + name_in(with, front_end) + " " +
                  one_of_text(g.row->applies_with_value) + " only, not " + holds);
  }
  options.validate();
  return options;
}

// A value as a record holds it: an infinite number is the word "inf".
OptionValue recorded(const OptionValue& value);

// The record of `options`: every field, in table order, as (key, value).
template <class Options>
std::vector<std::pair<std::string_view, OptionValue>> record_of(const Options& options) {
  std::vector<std::pair<std::string_view, OptionValue>> record;
  for (const Row<Options>& r : rows_of<Options>())
    if (r.is_field()) record.emplace_back(r.key, recorded(r.field.get(options)));
  return record;
}

// An option record read back from a file: (key, value as the file holds it: digits, a name or
// word, true / false), in any order.
using RecordedOptions = std::vector<std::pair<std::string, std::string>>;

// A field that changes the output and differs between two records; a field one record lacks is
// "not recorded" there.
struct OptionDifference {
  std::string key, before, after;
};

// Appends `key`'s difference between the records, if any. Numbers compare as numbers (1.2 and
// 1.20 are the same), everything else as text.
void add_difference(std::string_view key, const RecordedOptions& before,
                    const RecordedOptions& after, std::vector<OptionDifference>& differences);

// Whether a row that applies only while `applies_with_key` holds one of `applies_with_values`
// acts in `record` (a row without such a key always does). A row that acts in neither of two
// records cannot make their outputs differ: output_differences leaves it out, so that a record
// written before the row existed (the matcher's epipolar_band_px, added with matcher guided)
// still equals today's for every other matcher.
bool acts_in_record(std::string_view applies_with_key, std::string_view applies_with_values,
                    const RecordedOptions& record);

// The fields that change the output (rows with changes_output) whose values differ between
// `before` and `after`, in table order, among the rows that act in either record (above).
// Empty: outputs made with either record are the same bytes. Batch resume redoes an output with
// differences; merge refuses shards with them (io/option_record.hpp); match --pairs redoes pairs
// matched with other matcher options.
template <class Options = ExtractorOptions>
std::vector<OptionDifference> output_differences(const RecordedOptions& before,
                                                 const RecordedOptions& after) {
  std::vector<OptionDifference> differences;
  for (const Row<Options>& r : rows_of<Options>())
    if (r.is_field() && r.changes_output &&
        (acts_in_record(r.applies_with_key, r.applies_with_value, before) ||
         acts_in_record(r.applies_with_key, r.applies_with_value, after)))
      add_difference(r.key, before, after, differences);
  return differences;
}

// "n_features 500 -> 3000".
std::string text_of(const OptionDifference& difference);

}  // namespace aief::option_table

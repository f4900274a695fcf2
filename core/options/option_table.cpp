// The value code of the option tables (core/options/option_table.hpp): parsing and checking a
// value, its text, the option record and its differences, resolving given options, and
// ExtractorOptions' validate() and options_for_mode(). The rows are in their own files:
// core/options/extractor_option_rows.cpp, core/options/matching_option_rows.cpp.
#include "core/options/option_table.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <type_traits>

#include "aief/error.hpp"
#include "core/options/acts_with.hpp"
#include "core/options/detection_smoothing_values.hpp"
#include "core/options/option_access.hpp"
#include "core/options/option_names.hpp"

namespace aief::option_table {

namespace {

std::vector<std::string_view> split_words(std::string_view words) {
  std::vector<std::string_view> out;
  while (!words.empty()) {
    const std::size_t bar = words.find('|');
    out.push_back(words.substr(0, bar));
    words = bar == std::string_view::npos ? std::string_view() : words.substr(bar + 1);
  }
  return out;
}

std::string number_text(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;  // shortest round trip
  return std::string(buffer, end);
}

std::string range_text(const ValueSpec& spec) {
  const auto bound = [&](double v) {
    return spec.kind == ValueKind::integer ? std::to_string(static_cast<long long>(v))
                                           : number_text(v);
  };
  if (std::isinf(spec.high)) return (spec.low_is_open ? "> " : ">= ") + bound(spec.low);
  return std::string(spec.low_is_open ? "(" : "[") + bound(spec.low) + ", " + bound(spec.high) +
         (spec.high_is_open ? ")" : "]");
}

std::string joined(const std::vector<std::string_view>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? " or " : ", ";
    out += items[i];
  }
  return out;
}

bool in_range(const ValueSpec& spec, double value) {
  const bool above_low = spec.low_is_open ? value > spec.low : value >= spec.low;
  const bool below_high = spec.high_is_open ? value < spec.high : value <= spec.high;
  return above_low && below_high;
}

const OptionValue* mode_value(const OptionRow& row, Mode mode, OptionValue& storage, bool& fixed) {
  std::string_view text = row.per_mode[mode];
  fixed = !text.empty() && text[0] == '=';
  if (fixed) text.remove_prefix(1);
  if (text.empty()) return nullptr;
  storage = text == kDefault ? row.field.get(ExtractorOptions{}) : parse_value(row, text, row.key);
  return &storage;
}

}  // namespace

bool is_one_of(std::string_view values, std::string_view value) {
  const std::vector<std::string_view> words = split_words(values);
  return std::find(words.begin(), words.end(), value) != words.end();
}

std::string one_of_text(std::string_view values) {
  const std::vector<std::string_view> words = split_words(values);
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i)
    text += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + std::string(words[i]);
  return text;
}

bool parse_integer(std::string_view text, long long& value) {
  std::string_view digits = text;
  if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
  if (digits.empty() || (digits[0] == '-' && digits.size() == 1)) return false;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  return end == digits.data() + digits.size() &&
         error == std::errc();  // overflow: not a value here
}

bool parse_decimal(std::string_view text, double& value) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return i - from;
  };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  if (i != text.size()) return false;
  const std::string copy(text);
  errno = 0;
  value = std::strtod(copy.c_str(), nullptr);
  if (errno == ERANGE && std::isinf(value)) return false;
  if (value == 0) value = 0;  // -0 is 0
  return true;
}

std::string expected_values(const ValueSpec& spec) {
  const std::vector<std::string_view> words = split_words(spec.words);
  switch (spec.kind) {
    case ValueKind::integer: return "an integer in " + range_text(spec);
    case ValueKind::number: {
      std::vector<std::string_view> items;
      const std::string number =
          "a number " + std::string(std::isinf(spec.high) ? "" : "in ") + range_text(spec);
      items.push_back(number);
      items.insert(items.end(), words.begin(), words.end());
      return joined(items);
    }
    case ValueKind::choice: return joined(spec.choices()->names);
    case ValueKind::toggle: return joined(words);
  }
  return "";
}

OptionValue parse_value(const ValueSpec& spec, std::string_view text, std::string_view named) {
  const auto refuse = [&]() -> OptionValue {
    throw Error(std::string(named) + " expects " + expected_values(spec) + ", got '" +
                std::string(text) + "'");
  };
  switch (spec.kind) {
    case ValueKind::integer: {
      long long value = 0;
      if (!parse_integer(text, value) || !in_range(spec, static_cast<double>(value)))
        return refuse();
      return value;
    }
    case ValueKind::number: {
      for (std::string_view word : split_words(spec.words))
        if (text == word) return word;
      double value = 0;
      if (!parse_decimal(text, value) || !in_range(spec, value)) return refuse();
      return value;
    }
    case ValueKind::choice: {
      const ChoiceNames& choices = *spec.choices();
      for (std::size_t i = 0; i < choices.names.size(); ++i)
        if (text == choices.names[i] || text == choices.enumerators[i]) return choices.names[i];
      throw Error("unknown " + std::string(choices.what) + " '" + std::string(text) + "' for " +
                  std::string(named) + " (expected " + joined(choices.names) + ")");
    }
    case ValueKind::toggle: {
      const std::vector<std::string_view> words = split_words(spec.words);
      if (text == words[0] || text == "1") return true;  // 1 / 0: settings files' custom
      if (text == words[1] || text == "0") return false;
      return refuse();
    }
  }
  return refuse();
}

std::string text_of(const ValueSpec& spec, const OptionValue& value) {
  if (const bool* flag = std::get_if<bool>(&value))
    return std::string(split_words(spec.words)[*flag ? 0 : 1]);
  if (const long long* integer = std::get_if<long long>(&value)) return std::to_string(*integer);
  if (const double* number = std::get_if<double>(&value)) return number_text(*number);
  return std::string(std::get<std::string_view>(value));
}

std::string defaults_text(const OptionRow& row) {
  const ExtractorOptions defaults;
  std::string text = row.is_field() ? text_of(row, row.field.get(defaults))
                                    : std::string(option_names::name_of(Mode::aief));
  // The modes that set another value, grouped by value: "; scaled in aief-paper, orbslam2,
  // quadtree-entropy".
  std::vector<std::pair<std::string, std::string>> others;  // value, modes
  for (const auto& mode : option_names::Table<Mode>::names) {
    OptionValue storage;
    bool fixed = false;
    const OptionValue* value =
        row.is_field() ? mode_value(row, mode.value, storage, fixed) : nullptr;
    if (!value) continue;
    const std::string value_text = text_of(row, *value);
    if (value_text == text) continue;
    auto it = others.begin();
    while (it != others.end() && it->first != value_text) ++it;
    if (it == others.end())
      others.emplace_back(value_text, std::string(mode.name));
    else
      it->second += ", " + std::string(mode.name);
  }
  for (const auto& [value, modes] : others) text += "; " + value + " in " + modes;
  return text;
}

void check_value(std::string_view key, const ValueSpec& spec, const OptionValue& value) {
  bool ok = true;
  std::string shown;
  if (const long long* integer = std::get_if<long long>(&value)) {
    ok = in_range(spec, static_cast<double>(*integer));
    shown = std::to_string(*integer);
  } else if (const double* number = std::get_if<double>(&value)) {
    // A row whose words name infinity (the pool's "inf") takes it; NaN is never in range.
    const bool infinity_named = std::isinf(*number) && *number > 0 &&
                                std::string_view(spec.words).find("inf") != std::string_view::npos;
    ok = infinity_named || (std::isfinite(*number) && in_range(spec, *number));
    shown = number_text(*number);
  } else if (const std::string_view* name = std::get_if<std::string_view>(&value)) {
    if (*name == "?") throw Error(std::string(key) + " has an unknown value");
  }
  if (!ok) throw Error(std::string(key) + " must be " + expected_values(spec) + ", got " + shown);
}

OptionValue recorded(const OptionValue& value) {
  if (const double* number = std::get_if<double>(&value); number && std::isinf(*number))
    return std::string_view("inf");
  return value;
}

namespace {

// The value of `key` in `record`, or "not recorded".
std::string_view recorded_value(const RecordedOptions& record, std::string_view key) {
  for (const auto& [field, value] : record)
    if (field == key) return value;
  return "not recorded";
}

bool same_recorded_value(std::string_view a, std::string_view b) {
  if (a == b) return true;
  long long integer_a = 0, integer_b = 0;
  if (parse_integer(a, integer_a) && parse_integer(b, integer_b)) return integer_a == integer_b;
  double number_a = 0, number_b = 0;
  return parse_decimal(a, number_a) && parse_decimal(b, number_b) && number_a == number_b;
}

}  // namespace

bool acts_in_record(std::string_view applies_with_key, std::string_view applies_with_values,
                    const RecordedOptions& record) {
  return applies_with_key.empty() ||
         is_one_of(applies_with_values, recorded_value(record, applies_with_key));
}

void add_difference(std::string_view key, const RecordedOptions& before,
                    const RecordedOptions& after, std::vector<OptionDifference>& differences) {
  const std::string_view was = recorded_value(before, key), is = recorded_value(after, key);
  if (!same_recorded_value(was, is))
    differences.push_back({std::string(key), std::string(was), std::string(is)});
}

std::string text_of(const OptionDifference& difference) {
  // A record holds numbers at 17 digits (io/json_writer.cpp): shown by their shortest text, the
  // one that reads back as the same number (0.7, not 0.69999999999999996).
  const auto shown = [](const std::string& text) {
    long long integer = 0;
    double number = 0;
    if (parse_integer(text, integer) || !parse_decimal(text, number)) return text;
    return number_text(number);
  };
  return difference.key + " " + shown(difference.before) + " -> " + shown(difference.after);
}

namespace {

// A given option that a later one in table order undoes (entropy_threshold 3.0, whose setter turns
// the automatic F off, then auto_threshold on) would be dropped without a word: applied again to
// the resolved options, it changes them. Throws naming both and the field they disagree on.
void refuse_undone(const std::vector<const GivenOption*>& changed,
                   const std::vector<GivenOption>& given, const ExtractorOptions& options) {
  const auto resolved = record_of(options);
  for (const GivenOption* g : changed) {
    ExtractorOptions wanted = options;
    g->row->field.set(wanted, parse_value(*g->row, g->text, g->named));
    const auto wanted_record = record_of(wanted);
    if (wanted_record == resolved) continue;
    std::size_t field = 0;
    while (wanted_record[field] == resolved[field]) ++field;
    const OptionRow& differs = row(wanted_record[field].first);
    for (const GivenOption& later : given) {
      if (later.row == g->row || !later.row->is_field()) continue;
      ExtractorOptions both = wanted;
      later.row->field.set(both, parse_value(*later.row, later.text, later.named));
      if (record_of(both) == resolved)
        throw Error(g->named + " " + g->text + " means " + std::string(differs.key) + " " +
                    text_of(differs, wanted_record[field].second) + ", so " + later.named + " " +
                    later.text + " cannot apply: drop one of the two");
    }
  }
}

}  // namespace

ExtractorOptions resolve_options(const std::vector<GivenOption>& given, Use use) {
  Mode mode = Mode::aief;
  std::string mode_named = "mode";
  bool mode_given = false;
  const GivenOption* entropy_given = nullptr;
  for (const GivenOption& g : given) {
    if (g.row->key == "mode") {
      mode = option_names::parse<Mode>(
          std::get<std::string_view>(parse_value(*g.row, g.text, g.named)));
      mode_named = g.named;
      mode_given = true;
    }
    if (g.row->key == "entropy") entropy_given = &g;
  }
  ExtractorOptions options = options_for_mode(mode);
  const std::string mode_name(option_names::name_of(mode));
  // Options that need the mask and change a value (given the value the options hold, one changes
  // nothing and is no request: Extractor(**extractor.options) of an orbslam2 extractor).
  std::vector<const GivenOption*> needing_mask, changed;
  for (const OptionRow& row : rows()) {
    for (const GivenOption& g : given) {
      if (g.row != &row || !row.is_field()) continue;
      const OptionValue value = parse_value(row, g.text, g.named);
      OptionValue storage;
      bool fixed = false;
      const OptionValue* by_mode = mode_value(row, mode, storage, fixed);
      if (fixed && *by_mode != value)
        throw Error(mode_named + " " + mode_name + " means " + g.named + " " +
                    text_of(row, *by_mode) + ", so " + g.named + " " + g.text + " cannot apply");
      const auto before = record_of(options);
      row.field.set(options, value);
      if (record_of(options) == before) continue;
      changed.push_back(&g);
      if (!row.needs_mask.empty()) needing_mask.push_back(&g);
    }
  }
  refuse_undone(changed, given, options);
  if (options.entropy == EntropyMeasure::off)
    for (const GivenOption* g : needing_mask)
      throw Error(g->named + " " + std::string(g->row->needs_mask) + ", which " +
                  (entropy_given ? entropy_given->named + " off" : mode_named + " " + mode_name) +
                  " turns off: drop one of the two");
  std::vector<Mode> reference = {mode};
  if (!mode_given)
    for (Mode whole : modes_given_whole(given)) reference.push_back(whole);
  refuse_given_that_cannot_act(changed, given, options, reference, mode_named, mode, use);
  options.validate();
  return options;
}

}  // namespace aief::option_table

namespace aief {

// Generated from the table: each row's range and names; the rules that span fields follow.
namespace {

// Each pass count of the smoothing has one value (core/options/detection_smoothing_values.hpp):
// another sigma running the same passes would record another option for the same bytes.
void check_detection_smoothing(double sigma) {
  const int passes = detection_smoothing_passes(sigma);
  if (passes == 0 || sigma == detection_smoothing_of_passes(passes)) return;
  std::string accepted;
  const double highest = option_table::row("detection_smoothing").high;
  for (int p = 1; detection_smoothing_of_passes(p) <= highest; ++p)
    accepted += (p > 1 ? ", " : "") + option_table::number_text(detection_smoothing_of_passes(p));
  throw Error("detection_smoothing " + option_table::number_text(sigma) + " runs " +
              std::to_string(passes) + (passes == 1 ? " pass" : " passes") +
              " of the 5x5 binomial, as " +
              option_table::number_text(detection_smoothing_of_passes(passes)) +
              " does: give that (one value for each number of passes, so that equal option "
              "records mean equal outputs); the values are 0 (none), " +
              accepted);
}

}  // namespace

void ExtractorOptions::validate() const {
  option_table::check_fields(*this);
  // The pyramid computes in float (ORB-SLAM2's arithmetic, core/level/level_geometry.cpp): check
  // the value it will use, so 1.00000001 (1.0 as a float, which makes every level budget 0/0) is
  // refused rather than accepted and silently rounded.
  if (const float used = static_cast<float>(scale_factor); used <= 1.0f || used > 4.0f)
    throw Error(
        "scale_factor must be > 1 and <= 4 in single precision (the pyramid computes in float), "
        "got " +
        option_table::number_text(scale_factor) + (used == 1.0f ? ", which is 1 as a float" : ""));
  option_table::check_fields_act(*this);
  if (auto_threshold && carried_threshold)
    throw Error("auto_threshold and carried_threshold cannot both be on (one source of F)");
  if (fast_min_threshold > fast_threshold)
    throw Error("fast_min_threshold must be in [1, " + std::to_string(fast_threshold) +
                "] (at most fast_threshold), got " + std::to_string(fast_min_threshold));
  check_detection_smoothing(detection_smoothing);
}

// Each row's value for the mode, in table order, over `base`.
ExtractorOptions options_for_mode(Mode mode, ExtractorOptions base) {
  for (const option_table::OptionRow& row : option_table::rows()) {
    if (!row.is_field()) continue;
    option_table::OptionValue storage;
    bool fixed = false;
    if (const option_table::OptionValue* value =
            option_table::mode_value(row, mode, storage, fixed))
      row.field.set(base, *value);
  }
  return base;
}

}  // namespace aief

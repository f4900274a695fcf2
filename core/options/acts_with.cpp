#include "core/options/acts_with.hpp"

#include "aief/error.hpp"
#include "core/options/option_names.hpp"

namespace aief::option_table {

namespace {

// A field's value as text ("entropy", "30", "inf"), whatever made it.
std::string text_in(const OptionRow& row, const ExtractorOptions& options) {
  return text_of(row, row.field.get(options));
}

// A given value as the field holds it: through the row's setter, so "inf" and 1e400, "count"
// and false read alike.
std::string text_given(const GivenOption& g) {
  ExtractorOptions scratch;
  g.row->field.set(scratch, parse_value(*g.row, g.text, g.named));
  return text_in(*g.row, scratch);
}

// How the front end of `like` names `row`: the CLI by flags, a settings file by its keys, Python
// by keywords; the record key where the row has no such name.
std::string name_like(const OptionRow& row, const GivenOption& like) {
  std::string_view name = row.key;
  if (like.named == like.row->cli_flag && !row.cli_flag.empty())
    name = row.cli_flag;
  else if (like.named == like.row->yaml_key && !row.yaml_key.empty())
    name = row.yaml_key;
  else if (like.named != like.row->cli_flag && like.named != like.row->yaml_key &&
           !row.python_keyword.empty())
    name = row.python_keyword;
  return std::string(name);
}

// A field no front end sets by itself (distribution, auto_threshold, carried_threshold): which
// modes set `value`, else the row's own help ("set by --entropy-threshold carried").
std::string how_to_set(const OptionRow& row, const std::string& value) {
  if (row.has_front_ends()) return "";
  std::string modes;
  for (const auto& mode : option_names::Table<Mode>::names)
    if (text_in(row, options_for_mode(mode.value)) == value)
      modes += (modes.empty() ? "" : ", ") + std::string(mode.name);
  return " (" + (modes.empty() ? std::string(row.help) : "modes " + modes) + ")";
}

}  // namespace

UnmetCondition unmet_condition(const OptionRow& row, const ExtractorOptions& options) {
  std::string_view conditions = row.acts_with;
  while (!conditions.empty()) {
    const std::size_t comma = conditions.find(',');
    const std::string_view condition = conditions.substr(0, comma);
    conditions =
        comma == std::string_view::npos ? std::string_view() : conditions.substr(comma + 1);
    const std::size_t equals = condition.find('=');
    const OptionRow& needed = option_table::row(condition.substr(0, equals));
    const std::string value(condition.substr(equals + 1));
    if (std::string holds = text_in(needed, options); holds != value)
      return {&needed, value, std::move(holds)};
  }
  return {};
}

void check_fields_act(const ExtractorOptions& options) {
  for (const OptionRow& row : rows()) {
    // The variants (choices and switches); a number carried along in a struct (carry_every kept
    // while the carried F is turned off) is refused only when given (resolve_options).
    if (row.acts_with.empty() || row.kind() == ValueKind::integer ||
        row.kind() == ValueKind::number)
      continue;
    const UnmetCondition unmet = unmet_condition(row, options);
    if (!unmet.row) continue;
    const std::string value = text_in(row, options);
    bool held_by_a_preset = value == text_in(row, ExtractorOptions{});
    for (const auto& mode : option_names::Table<Mode>::names)
      held_by_a_preset = held_by_a_preset || value == text_in(row, options_for_mode(mode.value));
    if (!held_by_a_preset)
      throw Error(std::string(row.key) + " " + value + " does nothing unless " +
                  std::string(unmet.row->key) + " " + unmet.needed +
                  how_to_set(*unmet.row, unmet.needed) + ", and " + std::string(unmet.row->key) +
                  " is " + unmet.holds);
  }
}

std::vector<Mode> modes_given_whole(const std::vector<GivenOption>& given) {
  std::vector<Mode> whole;
  for (const auto& mode : option_names::Table<Mode>::names) {
    const ExtractorOptions preset = options_for_mode(mode.value);
    bool every_value_given = true, sets_any = false;
    for (const OptionRow& row : rows()) {
      if (!row.is_field() || row.per_mode[mode.value].empty()) continue;
      sets_any = true;
      bool found = false;
      for (const GivenOption& g : given)
        found = found || (g.row == &row && text_given(g) == text_in(row, preset));
      every_value_given = every_value_given && found;
    }
    if (sets_any && every_value_given) whole.push_back(mode.value);
  }
  return whole;
}

void refuse_given_that_cannot_act(const std::vector<const GivenOption*>& changed,
                                  const std::vector<GivenOption>& given,
                                  const ExtractorOptions& options,
                                  const std::vector<Mode>& reference, const std::string& mode_named,
                                  Mode mode, Use use) {
  for (const GivenOption* g : changed) {
    const OptionRow& row = *g->row;
    const std::string value = text_in(row, options);
    bool set_by_a_mode = false, set_by_a_mode_given_whole = false;
    for (Mode m : reference) {
      const bool sets = value == text_in(row, options_for_mode(m));
      set_by_a_mode = set_by_a_mode || sets;
      set_by_a_mode_given_whole = set_by_a_mode_given_whole || (sets && m != mode);
    }
    // A value of a mode given whole is no request in the sweep either (Extractor(**e.options) of
    // an aief-paper extractor gives its frame-wide guard back). The resolved mode's own values
    // are not asked: a given option that changed a value holds one of them only where its row
    // writes more than its field (entropy_threshold auto leaves F at the mode's 4).
    if (use == Use::sweep && !row.read_by_sweep && !set_by_a_mode_given_whole)
      throw Error(g->named + " " + g->text +
                  " does nothing in the adaptive sweep (aief adapt, match --adaptive), which tries "
                  "every F on the pair itself, without the threshold fallback: drop " +
                  g->named);
    if (row.acts_with.empty() || set_by_a_mode) continue;
    const UnmetCondition unmet = unmet_condition(row, options);
    if (!unmet.row || (use == Use::evaluation && unmet.row->key == "auto_threshold")) continue;
    // What holds the other field where it is: an option given, the mode, or the default.
    std::string stops;
    bool mode_given = false;
    for (const GivenOption& other : given) {
      if (other.row == unmet.row) stops = ", and " + other.named + " " + other.text + " is given";
      mode_given = mode_given || other.row->key == "mode";
    }
    const bool mode_sets =
        !unmet.row->per_mode[mode].empty() ||
        text_in(*unmet.row, options_for_mode(mode)) != text_in(*unmet.row, ExtractorOptions{});
    if (stops.empty() && mode_sets && (mode_given || mode != Mode::aief))
      stops = ", and " + mode_named + " " + std::string(option_names::name_of(mode)) +
              " makes it " + unmet.holds;
    const std::string needed =
        name_like(*unmet.row, *g) + " " + unmet.needed + how_to_set(*unmet.row, unmet.needed);
    throw Error(g->named + " " + g->text + " does nothing unless " + needed +
                (stops.empty() ? ", and it is " + unmet.holds + " by default: drop " + g->named
                               : stops + ": drop one of the two"));
  }
}

}  // namespace aief::option_table

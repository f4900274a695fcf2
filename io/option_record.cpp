#include "io/option_record.hpp"

#include <sstream>
#include <variant>

#include "core/options/option_table.hpp"

namespace aief::io {

namespace {

template <class Options>
void write_record(JsonWriter& json, const Options& options) {
  json.begin_object();
  for (const auto& [key, value] : option_table::record_of(options)) {
    json.key(key);
    std::visit([&](const auto& v) { json.value(v); }, value);
  }
  json.end_object();
}

template <class Options>
std::string record_json(const Options& options) {
  std::ostringstream out;
  JsonWriter json(out);
  json.set_newline_depth(0);
  write_record(json, options);
  std::string text = out.str();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

}  // namespace

void write_option_record(JsonWriter& json, const ExtractorOptions& options) {
  write_record(json, options);
}

std::string option_record_json(const ExtractorOptions& options) { return record_json(options); }

std::string match_option_record_json(const MatchOptions& options) { return record_json(options); }

namespace {

// The fields of a flat JSON object of scalars (what write_option_record writes), values as
// written with strings unquoted; nullopt when `text` is not one.
std::optional<option_table::RecordedOptions> read_option_record_json(std::string_view text) {
  option_table::RecordedOptions fields;
  std::size_t at = 0;
  const auto skip_space = [&] {
    while (at < text.size() &&
           (text[at] == ' ' || text[at] == '\n' || text[at] == '\r' || text[at] == '\t'))
      ++at;
  };
  // A string without escapes (keys and names never hold one); false when there is none.
  const auto read_string = [&](std::string& out) {
    if (at >= text.size() || text[at] != '"') return false;
    const std::size_t end = text.find('"', at + 1);
    if (end == std::string_view::npos ||
        text.substr(at + 1, end - at - 1).find('\\') != std::string_view::npos)
      return false;
    out = std::string(text.substr(at + 1, end - at - 1));
    at = end + 1;
    return true;
  };
  skip_space();
  if (at >= text.size() || text[at++] != '{') return std::nullopt;
  skip_space();
  if (at < text.size() && text[at] == '}') return fields;
  while (true) {
    std::string key, value;
    skip_space();
    if (!read_string(key)) return std::nullopt;
    skip_space();
    if (at >= text.size() || text[at++] != ':') return std::nullopt;
    skip_space();
    if (at < text.size() && text[at] == '"') {
      if (!read_string(value)) return std::nullopt;
    } else {
      const std::size_t end = text.find_first_of(",} \n\r\t", at);
      if (end == std::string_view::npos || end == at) return std::nullopt;
      value = std::string(text.substr(at, end - at));
      at = end;
    }
    fields.emplace_back(std::move(key), std::move(value));
    skip_space();
    if (at >= text.size()) return std::nullopt;
    if (text[at] == '}') return fields;
    if (text[at++] != ',') return std::nullopt;
  }
}

template <class Options = ExtractorOptions>
std::vector<std::string> changes_between(
    const std::optional<option_table::RecordedOptions>& first,
    const std::optional<option_table::RecordedOptions>& other) {
  if (!first || !other) return {std::string(kNoOptionRecord)};
  std::vector<std::string> changes;
  for (const auto& difference : option_table::output_differences<Options>(*first, *other))
    changes.push_back(option_table::text_of(difference));
  return changes;
}

}  // namespace

std::vector<std::string> option_changes(const std::optional<std::string>& recorded,
                                        const ExtractorOptions& options) {
  return changes_between(recorded ? read_option_record_json(*recorded) : std::nullopt,
                         read_option_record_json(option_record_json(options)));
}

std::vector<std::string> option_changes(const std::string& first, const std::string& other) {
  return changes_between(read_option_record_json(first), read_option_record_json(other));
}

std::vector<std::string> match_option_changes(const std::string& first, const std::string& other) {
  return changes_between<MatchOptions>(read_option_record_json(first),
                                       read_option_record_json(other));
}

DescriptorKind recorded_descriptor(const std::optional<std::string>& recorded) {
  if (!recorded || recorded->empty()) return DescriptorKind::rbrief;
  const std::optional<option_table::RecordedOptions> fields = read_option_record_json(*recorded);
  if (fields)
    for (const auto& [key, value] : *fields)
      if (key == "descriptor") return parse_descriptor_kind(value);
  return DescriptorKind::rbrief;
}

std::string listed(const std::vector<std::string>& changes) {
  std::string text;
  for (const std::string& change : changes) text += (text.empty() ? "" : ", ") + change;
  return text;
}

}  // namespace aief::io

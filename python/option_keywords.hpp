#pragma once
// A Python call's arguments read by the option tables (core/options/option_table.hpp): the
// function's leading parameters (images, an extractor), then the options of one or more structs, by
// position in the rows' python_position order (struct after struct) or by keyword. None means
// not given. Extractor(), match(), find_homography() and adapt() take their options this way, so
// a keyword, its position and its default are written only in the row.
#include <string>
#include <vector>

#include "core/options/option_table.hpp"
#include "python/bindings.hpp"

namespace aief::python {

namespace table = option_table;

// One keyword of a call.
struct Keyword {
  std::string name;  // as the caller writes it
  table::ValueSpec spec;
  const void* row;  // the table::Row<Options> of its group
  int group;        // which options struct
  int position;     // 1, 2, ... within the call's options; 0: keyword only; -1: a record key
  py::object default_value;  // python_default of the row
};

// The Python default of a row, as the stub and the docstrings show it: None where the value
// depends on other options (the extractor's mode sets it, or it applies with another option
// only: ratio), else the struct's default.
py::object python_default(const table::OptionValue& value, bool depends_on_others);
template <class Options>
py::object python_default(const table::Row<Options>& row) {
  const bool depends = !row.applies_with_key.empty() || row.per_mode.any();
  if (!row.is_field()) return py::str(table::defaults_text(row));  // the mode: its default name
  return python_default(row.field.get(Options{}), depends);
}

class OptionCall {
 public:
  // `function` names the call in messages; `leading` its parameters before the options, the
  // first `required` of them required.
  OptionCall(std::string function, std::vector<std::string> leading, std::size_t required);

  // Adds the keywords of `Options`' rows as the next group. `record_keys`: each field row's
  // record key is a keyword too (what Extractor.options holds), so Extractor(**e.options)
  // rebuilds e. A row's earlier keyword is accepted too, outside the signature.
  template <class Options>
  int add_group(bool record_keys = false) {
    const int group = groups_++;
    const int first_position = static_cast<int>(positional_count());
    for (const table::Row<Options>& row : table::rows_of<Options>()) {
      const int position = row.python_position > 0 ? first_position + row.python_position : 0;
      if (!row.python_keyword.empty())
        keywords_.push_back({std::string(row.python_keyword), row.spec(), &row, group, position,
                             python_default(row)});
      if (record_keys && row.is_field() && row.key != row.python_keyword)
        keywords_.push_back({std::string(row.key), row.spec(), &row, group, -1, py::none()});
      if (!row.old_python_keyword.empty())  // an earlier spelling, still accepted (CHANGELOG.md)
        keywords_.push_back(
            {std::string(row.old_python_keyword), row.spec(), &row, group, -1, py::none()});
    }
    return group;
  }

  // Reads the call: throws TypeError as Python does for too many positionals, an unknown keyword
  // or a value given twice, and for a value of the wrong type.
  void read(const py::args& args, const py::kwargs& kwargs);

  // "match(a, b, matcher='mutual', ratio=None, max_distance=256)": the call as the stub writes
  // it, keyword-only parameters after a '*' (record keys left out).
  std::string signature() const;
  const std::string& function() const { return function_; }

  // The i-th leading parameter (None when not given).
  py::object leading(std::size_t i) const { return leading_[i]; }

  // The options given to `group`, as the table resolves them.
  template <class Options>
  std::vector<table::Given<Options>> given(int group) const {
    std::vector<table::Given<Options>> out;
    for (const GivenText& g : given_)
      if (g.keyword->group == group)
        out.push_back(
            {static_cast<const table::Row<Options>*>(g.keyword->row), g.text, g.keyword->name});
    return out;
  }
  template <class Options>
  Options options(int group, Options base = {}) const {
    return table::resolve_options(given<Options>(group), table::FrontEnd::python, base);
  }

 private:
  struct GivenText {
    const Keyword* keyword;
    std::string text;
  };
  std::size_t positional_count() const;

  std::string function_;
  std::vector<std::string> leading_names_;
  std::size_t required_;
  std::vector<py::object> leading_;
  std::vector<Keyword> keywords_;
  std::vector<GivenText> given_;
  int groups_ = 0;
};

// The signatures of the calls bound so far, by function name (the test hook _signatures, which
// python/tests/test_stub.py holds against aief/_aief.pyi).
void keep_signature(const OptionCall& call);
std::vector<std::pair<std::string, std::string>> kept_signatures();

// A docstring's list of keywords: "  matcher: which ... (mutual, ratio or paper; default mutual)".
template <class Options>
std::string keywords_doc() {
  std::string doc;
  for (const table::Row<Options>& row : table::rows_of<Options>()) {
    if (row.python_keyword.empty()) continue;
    doc += "  " + std::string(row.python_keyword) + ": " + std::string(row.help) + " (";
    if (row.kind() == table::ValueKind::choice)
      doc += table::expected_values(row) + "; ";
    else if (row.kind() == table::ValueKind::toggle)
      doc += "True / False; ";
    doc += "default " + table::defaults_text(row) + ")\n";
  }
  return doc;
}

}  // namespace aief::python

#include "python/option_keywords.hpp"

#include <algorithm>

namespace aief::python {

namespace {

bool is_bool(const py::handle& value) {
  const std::string type = py::str(py::type::of(value).attr("__name__"));
  return py::isinstance<py::bool_>(value) || type == "bool_" || type == "bool";  // numpy.bool_ too
}

[[noreturn]] void wrong_type(const std::string& keyword, const py::handle& value,
                             const char* wanted) {
  throw py::type_error(keyword + " must be " + wanted + ", got " + std::string(py::repr(value)) +
                       " (" + py::type::of(value).attr("__name__").cast<std::string>() + ")");
}

// A keyword's value as the text the option table parses: integers by their digits, numbers by
// their shortest repr (which reads back as the same double), names and words as they are. numpy
// scalars count as the numbers they are; a bool is no number. Wrong types raise TypeError; wrong
// values raise aief.Error from the table's parser, as the CLI's do.
std::string text_of_keyword(const Keyword& keyword, const py::handle& value) {
  const bool is_text = py::isinstance<py::str>(value);
  switch (keyword.spec.kind) {
    case table::ValueKind::integer:
      if (is_bool(value) || !PyIndex_Check(value.ptr()))
        wrong_type(keyword.name, value, "an integer");
      return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())));
    case table::ValueKind::number:
      if (is_text && !keyword.spec.words.empty()) return value.cast<std::string>();
      if (is_bool(value) || is_text || !PyNumber_Check(value.ptr()))
        wrong_type(keyword.name, value,
                   keyword.spec.words.empty() ? "a number" : "a number or a word");
      return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
    case table::ValueKind::choice:
      if (!is_text) wrong_type(keyword.name, value, "a name (str)");
      return value.cast<std::string>();
    case table::ValueKind::toggle:
      if (is_text) return value.cast<std::string>();
      if (!is_bool(value)) wrong_type(keyword.name, value, "a bool");
      return table::text_of(keyword.spec, value.cast<bool>());
  }
  return {};
}

}  // namespace

py::object python_default(const table::OptionValue& value, bool depends_on_others) {
  if (depends_on_others) return py::none();
  if (const bool* flag = std::get_if<bool>(&value)) return py::bool_(*flag);
  if (const long long* integer = std::get_if<long long>(&value)) return py::int_(*integer);
  if (const double* number = std::get_if<double>(&value)) return py::float_(*number);
  return py::str(std::string(std::get<std::string_view>(value)));
}

OptionCall::OptionCall(std::string function, std::vector<std::string> leading, std::size_t required)
    : function_(std::move(function)),
      leading_names_(std::move(leading)),
      required_(required),
      leading_(leading_names_.size(), py::none()) {}

std::size_t OptionCall::positional_count() const {
  return static_cast<std::size_t>(std::count_if(keywords_.begin(), keywords_.end(),
                                                [](const Keyword& k) { return k.position > 0; }));
}

std::string OptionCall::signature() const {
  std::string text = function_ + "(";
  std::string separator;
  for (std::size_t i = 0; i < leading_names_.size(); ++i) {
    text += separator + leading_names_[i] + (i < required_ ? "" : "=None");
    separator = ", ";
  }
  std::vector<const Keyword*> positional(positional_count());
  for (const Keyword& k : keywords_)
    if (k.position > 0) positional[static_cast<std::size_t>(k.position - 1)] = &k;
  const auto parameter = [&](const Keyword& k) {
    text += separator + k.name + "=" + std::string(py::repr(k.default_value));
    separator = ", ";
  };
  for (const Keyword* k : positional) parameter(*k);
  bool starred = false;
  for (const Keyword& k : keywords_) {
    if (k.position != 0) continue;
    if (!starred) text += separator + "*";
    starred = true;
    separator = ", ";
    parameter(k);
  }
  return text + ")";
}

void OptionCall::read(const py::args& args, const py::kwargs& kwargs) {
  std::vector<const Keyword*> positional(positional_count());
  for (const Keyword& k : keywords_)
    if (k.position > 0) positional[static_cast<std::size_t>(k.position - 1)] = &k;
  const std::size_t most = leading_names_.size() + positional.size();
  if (args.size() > most)
    throw py::type_error(function_ + "() takes at most " + std::to_string(most) +
                         " positional arguments (" + std::to_string(args.size()) + " given)");
  std::vector<bool> leading_given(leading_names_.size(), false);
  std::vector<std::pair<const Keyword*, py::handle>> values;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (i < leading_names_.size()) {
      leading_[i] = py::reinterpret_borrow<py::object>(args[i]);
      leading_given[i] = true;
    } else {
      values.emplace_back(positional[i - leading_names_.size()], args[i]);
    }
  }
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const auto twice = [&] {
      throw py::type_error(function_ + "() got multiple values for argument '" + name + "'");
    };
    const auto leading = std::find(leading_names_.begin(), leading_names_.end(), name);
    if (leading != leading_names_.end()) {
      const auto i = static_cast<std::size_t>(leading - leading_names_.begin());
      if (leading_given[i]) twice();
      leading_[i] = py::reinterpret_borrow<py::object>(value);
      leading_given[i] = true;
      continue;
    }
    const Keyword* keyword = nullptr;
    for (const Keyword& k : keywords_)
      if (k.name == name) keyword = &k;
    if (!keyword)
      throw py::type_error(function_ + "() got an unexpected keyword argument '" + name + "'");
    for (const auto& [given, unused] : values)
      if (given->row == keyword->row) twice();  // a row by its keyword and its record key
    values.emplace_back(keyword, value);
  }
  for (std::size_t i = 0; i < required_; ++i)
    if (!leading_given[i])
      throw py::type_error(function_ + "() missing required argument '" + leading_names_[i] + "'");
  given_.clear();
  for (const auto& [keyword, value] : values)
    if (!value.is_none()) given_.push_back({keyword, text_of_keyword(*keyword, value)});
}

namespace {

std::vector<std::pair<std::string, std::string>>& signatures() {
  static std::vector<std::pair<std::string, std::string>> kept;
  return kept;
}

}  // namespace

void keep_signature(const OptionCall& call) {
  signatures().emplace_back(call.function(), call.signature());
}

std::vector<std::pair<std::string, std::string>> kept_signatures() { return signatures(); }

}  // namespace aief::python

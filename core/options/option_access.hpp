#pragma once
// A row's field access made from a member pointer (core/options/option_table.hpp):
// access<&Options::x> reads and writes the field as the table's OptionValue, its kind taken from
// the field's type (int -> integer, double -> number, bool -> toggle, enum -> choice, with the
// enum's name table of core/options/option_names.hpp), and AIEF_OPTION_ROW writes a row's key and
// access from the field's name. The tables' files (core/options/extractor_option_rows.cpp,
// core/options/matching_option_rows.cpp) use it; nothing else needs it.
#include <type_traits>

#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"

namespace aief::option_table {

template <class Enum>
const ChoiceNames* choices_of() {
  static const ChoiceNames names = [] {
    ChoiceNames out{option_names::Table<Enum>::what, {}, {}};
    for (const auto& n : option_names::Table<Enum>::names) {
      out.names.push_back(n.name);
      out.enumerators.push_back(n.enumerator);
    }
    return out;
  }();
  return &names;
}

// The struct and the type of a member pointer.
template <class Member>
struct MemberOf;
template <class Struct, class Field>
struct MemberOf<Field Struct::*> {
  using Options = Struct;
  using Type = std::decay_t<Field>;
};

template <auto Member>
OptionValue get_field(const typename MemberOf<decltype(Member)>::Options& options) {
  const auto& value = options.*Member;
  using T = typename MemberOf<decltype(Member)>::Type;
  if constexpr (std::is_enum_v<T>)
    return option_names::name_of(value);
  else if constexpr (std::is_same_v<T, bool>)
    return value;
  else if constexpr (std::is_integral_v<T>)
    return static_cast<long long>(value);
  else
    return static_cast<double>(value);
}

template <auto Member>
void set_field(typename MemberOf<decltype(Member)>::Options& options, const OptionValue& value) {
  auto& field = options.*Member;
  using T = typename MemberOf<decltype(Member)>::Type;
  if constexpr (std::is_enum_v<T>)
    field = option_names::parse<T>(std::get<std::string_view>(value));
  else if constexpr (std::is_same_v<T, bool>)
    field = std::get<bool>(value);
  else if constexpr (std::is_integral_v<T>)
    field = static_cast<T>(std::get<long long>(value));
  else
    field = std::get<double>(value);
}

template <class T>
constexpr ValueKind kind_of() {
  if constexpr (std::is_enum_v<T>)
    return ValueKind::choice;
  else if constexpr (std::is_same_v<T, bool>)
    return ValueKind::toggle;
  else if constexpr (std::is_integral_v<T>)
    return ValueKind::integer;
  else
    return ValueKind::number;
}

// A field's access, from its member pointer: kind, get, set and (enums) names.
template <auto Member>
constexpr FieldAccess<typename MemberOf<decltype(Member)>::Options> access = [] {
  using T = typename MemberOf<decltype(Member)>::Type;
  FieldAccess<typename MemberOf<decltype(Member)>::Options> a{kind_of<T>(), get_field<Member>,
                                                              set_field<Member>, nullptr};
  if constexpr (std::is_enum_v<T>) a.choices = choices_of<T>;
  return a;
}();

}  // namespace aief::option_table

// A row's key and field access from the member's name, in a table whose options struct is `O` (a
// `using O = ...;` before the table): the name written once, as AIEF_RECORD_FIELD writes a record
// field's (io/record_fields.hpp). The _WITH_SET form gives the field a setter of its own (F's
// words, P's "inf").
#define AIEF_OPTION_ROW(member) .key = #member, .field = ::aief::option_table::access<&O::member>
#define AIEF_OPTION_ROW_WITH_SET(member, setter) \
  .key = #member, .field = ::aief::option_table::access<&O::member>.with_set(setter)

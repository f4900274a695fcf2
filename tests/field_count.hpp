#pragma once
// The number of fields of an aggregate, the most initialisers it takes: what the option-table
// tests compare with the rows, so that a field without a row fails (tests/test_option_table.cpp,
// tests/test_matching_option_rows.cpp).
#include <cstddef>

namespace aief::test {

struct AnyValue {
  template <class T>
  operator T() const;
};

template <class T, class... Values>
constexpr std::size_t field_count() {
  if constexpr (requires { T{Values{}..., AnyValue{}}; })
    return field_count<T, Values..., AnyValue>();
  else
    return sizeof...(Values);
}

}  // namespace aief::test

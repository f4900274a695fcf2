#include "core/description/level_descriptor.hpp"

#include <cstddef>
#include <iterator>
#include <string>
#include <type_traits>
#include <utility>

#include "aief/error.hpp"
#include "core/options/option_names.hpp"

namespace aief {

namespace {

// Each row is a LevelDescriptor and sits at its kind's place, so a kind picks its row by index.
template <std::size_t... I>
constexpr bool rows_in_kind_order(std::index_sequence<I...>) {
  return ((LevelDescriptor<std::variant_alternative_t<I, LevelDescriptors>> &&
           static_cast<std::size_t>(std::variant_alternative_t<I, LevelDescriptors>::kKind) == I) &&
          ...);
}
static_assert(rows_in_kind_order(std::make_index_sequence<std::variant_size_v<LevelDescriptors>>{}),
              "LevelDescriptors: one LevelDescriptor per DescriptorKind, in its order");
// and a DescriptorKind with a name (core/options/option_names.hpp) has its row.
static_assert(std::variant_size_v<LevelDescriptors> ==
                  std::size(option_names::Table<DescriptorKind>::names),
              "LevelDescriptors: a row for every DescriptorKind");

template <std::size_t I = 0>
LevelDescriptors row_at(std::size_t index) {
  if constexpr (I == std::variant_size_v<LevelDescriptors>) {
    throw Error("no descriptor row for DescriptorKind " + std::to_string(index));
  } else {
    if (index == I) return LevelDescriptors(std::in_place_index<I>);
    return row_at<I + 1>(index);
  }
}

}  // namespace

LevelDescriptors level_descriptor_of(DescriptorKind kind) {
  return row_at(static_cast<std::size_t>(kind));
}

DescriptorKind kind_of(const LevelDescriptors& descriptor) {
  return std::visit([](const auto& row) { return std::decay_t<decltype(row)>::kKind; }, descriptor);
}

}  // namespace aief

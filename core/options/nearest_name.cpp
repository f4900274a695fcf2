#include "core/options/nearest_name.hpp"

#include <algorithm>
#include <cctype>

namespace aief::option_table {

namespace {

int lower(char c) { return std::tolower(static_cast<unsigned char>(c)); }

// Levenshtein distance, one row at a time.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min(
          {row[j] + 1, row[j - 1] + 1, diagonal + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearest_name(std::string_view name, const std::vector<std::string_view>& known) {
  std::string best;
  std::size_t best_distance = name.size() / 3 + 1;
  for (std::string_view candidate : known)
    if (const std::size_t d = edit_distance(name, candidate); d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  return best;
}

}  // namespace aief::option_table

#include "core/kernels/bound_filter.hpp"

#include <algorithm>

namespace aief {

int positions_within_bounds_scalar(const std::uint16_t* distances, const std::int16_t* train_bounds,
                                   int n, int query_bound, std::int32_t* positions) {
  int count = 0;
  for (int k = 0; k < n; ++k) {
    positions[count] = k;  // written always, kept when it passes: no branch on the data
    count += static_cast<std::int16_t>(distances[k]) <= std::max<int>(query_bound, train_bounds[k]);
  }
  return count;
}

}  // namespace aief

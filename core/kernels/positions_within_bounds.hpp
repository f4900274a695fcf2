#pragma once
// The filter in front of the sweep matcher's neighbour lists (core/sweep/sweep_matcher.cpp): of a
// row of distances, the few that some list would still take. A pair (query, train k) at distance d
// is worth offering when d <= the query list's bound or d <= train k's list's bound; most of a
// row is above both, so the positions are found a vector at a time.
#include <cstdint>

namespace aief {

// Writes, in ascending order, the positions k in [0, n) with
// distances[k] <= max(query_bound, train_bounds[k]) (compared as signed 16-bit values) and
// returns how many. Reads exactly n elements of each array; `positions` has room for n.
int positions_within_bounds_scalar(const std::uint16_t* distances, const std::int16_t* train_bounds,
                                   int n, int query_bound, std::int32_t* positions);

}  // namespace aief

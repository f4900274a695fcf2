#pragma once
// The bookkeeping both matchers share (core/match/matcher.cpp, core/match/guided_matcher.cpp):
// each row's nearest and second nearest train, and the nearest query of each train merged from
// the per-band column minima their parallel bands of rows keep. Bands in order, a lower distance
// wins and ties keep the lower index, so the answer does not depend on how the bands were
// scheduled.
#include <cstddef>
#include <limits>
#include <vector>

namespace aief {

// Nearest and second nearest train of one query, offered in ascending train order.
struct Nearest {
  int best = -1, best_distance = std::numeric_limits<int>::max();
  int second_distance = std::numeric_limits<int>::max();

  void offer(int distance, int train) {
    if (distance < best_distance) {
      second_distance = best_distance;
      best_distance = distance;
      best = train;
    } else if (distance < second_distance) {
      second_distance = distance;
    }
  }
};

// band_distance[b * n_train + j], band_best[b * n_train + j]: band b's nearest query of train j
// (max int and -1 where it saw none). Returns each train's nearest query, -1 for none.
inline std::vector<int> merge_band_column_minima(int bands, int n_train,
                                                 const std::vector<int>& band_distance,
                                                 const std::vector<int>& band_best) {
  std::vector<int> best(static_cast<std::size_t>(n_train), -1);
  std::vector<int> distance(static_cast<std::size_t>(n_train), std::numeric_limits<int>::max());
  for (int band = 0; band < bands; ++band)
    for (int j = 0; j < n_train; ++j) {
      const std::size_t k = static_cast<std::size_t>(band) * n_train + j;
      if (band_distance[k] < distance[static_cast<std::size_t>(j)]) {
        distance[static_cast<std::size_t>(j)] = band_distance[k];
        best[static_cast<std::size_t>(j)] = band_best[k];
      }
    }
  return best;
}

}  // namespace aief

#pragma once
// How the adaptive sweep cuts its distinct thresholds into runs, one per thread (core/
// adaptive_sweep.cpp). A run matches its first threshold in full and each later one only for the
// features new to it (core/sweep/sweep_matcher.hpp), so equal numbers of thresholds per run can be
// far from equal work: the cut is placed on estimated costs instead. The answers never depend on
// it.
#include <vector>

namespace aief {

// Cuts thresholds [0, n) into `runs` runs of consecutive thresholds (1 <= runs <= n), each run
// non-empty, so that the largest run cost is as small as possible; ties go to the earliest cuts.
// A run [j, k) costs fresh[j] + incremental[j + 1] + ... + incremental[k - 1]. Returns runs + 1
// boundaries: run r is [begin[r], begin[r + 1]), begin[0] = 0, begin[runs] = n.
std::vector<int> balanced_runs(const std::vector<double>& fresh,
                               const std::vector<double>& incremental, int runs);

}  // namespace aief

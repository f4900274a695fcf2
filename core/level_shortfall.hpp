#pragma once
// The shortfall of the level budgets (issue 8 item 8, DESIGN.md section 3), part of the per-level
// starvation rule of the aief mode: after every level has selected at its budget N_n, a level
// whose kept blocks hold fewer candidates than N_n leaves the difference undelivered (graf,
// --levels 20: 991 of 1000). That shortfall goes to the levels that still have unselected
// candidates in their kept blocks, finest level first (level 0 takes all it can, then level 1,
// ...): the finest levels have the most candidates and the most precise positions. The frame then
// delivers min(N, candidates in the kept blocks of every level).
#include <cstdint>
#include <vector>

namespace aief {

// Raised budgets: `budgets[n]` is N_n, `available[n]` the candidates in level n's kept blocks.
// Every level delivers min(budget, available); the sum of max(0, N_n - available_n) is handed out
// finest level first, each level taking at most available_n - N_n more. `raised` gets the new
// budgets (equal to `budgets` when there is no shortfall or no level can take it). Returns whether
// any budget was raised.
bool raise_budgets_for_shortfall(const std::vector<int>& budgets, const std::vector<std::int64_t>& available,
                                 std::vector<int>& raised);

}  // namespace aief

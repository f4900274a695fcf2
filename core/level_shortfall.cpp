#include "core/level_shortfall.hpp"

#include <algorithm>
#include <cassert>

namespace aief {

bool raise_budgets_for_shortfall(const std::vector<int>& budgets, const std::vector<std::int64_t>& available,
                                 std::vector<int>& raised) {
  assert(budgets.size() == available.size());
  raised.assign(budgets.begin(), budgets.end());
  std::int64_t shortfall = 0;
  for (std::size_t n = 0; n < budgets.size(); ++n)
    shortfall += std::max<std::int64_t>(0, budgets[n] - available[n]);
  bool any = false;
  for (std::size_t n = 0; n < budgets.size() && shortfall > 0; ++n) {
    const std::int64_t extra = std::min(shortfall, available[n] - budgets[n]);
    if (extra <= 0) continue;
    raised[n] = budgets[n] + static_cast<int>(extra);
    shortfall -= extra;
    any = true;
  }
  return any;
}

}  // namespace aief

#include "core/options/detection_smoothing_values.hpp"

#include <algorithm>
#include <cmath>

namespace aief {

int detection_smoothing_passes(double sigma) {
  if (!(sigma > 0)) return 0;
  return std::max(1, static_cast<int>(std::lround(sigma * sigma)));
}

double detection_smoothing_of_passes(int passes) {
  // The least t with t^2 >= 100 p, in integers: 10 sqrt(p) rounded up, exactly.
  long long tenths = static_cast<long long>(std::sqrt(100.0 * passes));
  while (tenths * tenths < 100LL * passes) ++tenths;
  while (tenths > 0 && (tenths - 1) * (tenths - 1) >= 100LL * passes) --tenths;
  return static_cast<double>(tenths) / 10;
}

}  // namespace aief

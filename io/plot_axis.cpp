#include "io/plot_axis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aief::io {

std::string AxisTicks::label(double value) const {
  int decimals = 0;  // enough to tell two ticks apart: 2.5 x 10^k needs one more than 10^k
  for (double s = step;
       decimals < 6 && std::abs(s - std::round(s)) > 1e-9 * std::max(1.0, std::abs(s)); s *= 10)
    ++decimals;
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value == 0 ? 0.0 : value);  // no "-0"
  return buffer;
}

AxisTicks round_ticks(double lo, double hi, int target) {
  if (!(std::isfinite(lo) && std::isfinite(hi))) lo = 0, hi = 1;
  if (lo > hi) std::swap(lo, hi);
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) lo -= 0.5, hi += 0.5;
  target = std::max(target, 1);
  const double raw = (hi - lo) / target;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * power;
  for (const double m : {1.0, 2.0, 2.5, 5.0})
    if (m * power >= raw * (1 - 1e-9)) {
      step = m * power;
      break;
    }
  AxisTicks ticks;
  ticks.step = step;
  const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
  for (double k = first; k <= last + 0.5; ++k) ticks.values.push_back(k * step);
  if (ticks.values.size() < 2) ticks.values.push_back((last + 1) * step);
  return ticks;
}

}  // namespace aief::io

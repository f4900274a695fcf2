#pragma once
// Axis ticks a reader can read: round values (1, 2, 2.5 or 5 times a power of ten) spanning the
// data, the axis stretched to the outer ticks, labels with no more decimals than the step needs.
#include <string>
#include <vector>

namespace aief::io {

struct AxisTicks {
  std::vector<double>
      values;  // ascending, evenly spaced by step; front() <= data minimum, back() >= data maximum
  double step = 1;
  std::string label(double value) const;  // "250", "0.5", "2.5": the decimals of the step
};

// About `target` intervals (never fewer than 2 ticks) covering [lo, hi]; lo == hi gets a unit span.
AxisTicks round_ticks(double lo, double hi, int target = 5);

}  // namespace aief::io

#pragma once
// The values of ExtractorOptions::detection_smoothing and what they run (docs/design.md §5,
// "detection on a smoothed level"; the blur itself is core/detection/detection_smoothing.hpp). A
// sigma s > 0 runs max(1, round(s^2)) passes of the 5x5 binomial (sigma 1 a pass; variances add,
// so p passes blur by sqrt(p)): 0.5, 1 and 1.2 all run one pass. So that equal option records
// mean equal bytes (batch resume and merge compare records, io/option_record.hpp), each pass count
// has one value, sqrt(p) rounded up to a tenth (1, 1.5, 1.8, 2, 2.3, 2.5, 2.7, 2.9, 3), and
// validate() refuses any other sigma, naming the one that runs the same passes.
namespace aief {

// Passes of the binomial blur for a smoothing sigma (0: none).
int detection_smoothing_passes(double sigma);

// The value that names `passes` (>= 1) passes: sqrt(passes) rounded up to a tenth.
double detection_smoothing_of_passes(int passes);

}  // namespace aief

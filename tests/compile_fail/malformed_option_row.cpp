// A table with one malformed row, AIEF_BAD_ROW choosing which (1 a second row of a key, 2 low >
// high, 3 a mode without its value, 4 a newline in the help): it must not compile. The CTests
// malformed_option_row_* (tests/CMakeLists.txt) compile it and expect AIEF_CHECK_OPTION_ROWS's
// message; without AIEF_BAD_ROW it compiles, which shows the file itself is sound.
#include "core/options/malformed_row.hpp"
#include "core/options/option_access.hpp"

namespace aief::option_table {

using O = ExtractorOptions;  // AIEF_OPTION_ROW's struct

constexpr OptionRow kRows[] = {
    {AIEF_OPTION_ROW(n_features), .cli_flag = "--n-features", .help = "keypoints", .low = 1,
     .high = 1000},
#if AIEF_BAD_ROW == 1
    {AIEF_OPTION_ROW(n_features), .help = "keypoints again"},
#elif AIEF_BAD_ROW == 2
    {AIEF_OPTION_ROW(n_levels), .help = "levels", .low = 32, .high = 1},
#elif AIEF_BAD_ROW == 3
    {AIEF_OPTION_ROW(n_levels), .help = "levels", .low = 1, .high = 32,
     .per_mode = {.aief = "", .aief_paper = "", .orbslam2 = "", .faithful = "", .quality = "18"}},
#elif AIEF_BAD_ROW == 4
    {AIEF_OPTION_ROW(n_levels), .help = "pyramid\nlevels", .low = 1, .high = 32},
#endif
};
AIEF_CHECK_OPTION_ROWS(kRows);

}  // namespace aief::option_table

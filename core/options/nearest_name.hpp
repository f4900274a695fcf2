#pragma once
// The known name nearest to a misspelt one, for "unknown key 'x' (did you mean 'y'?)": the
// settings reader's ORBextractor.* keys (opencv/orbslam_extractor_base.cpp) and Feature2D::read's
// keys (opencv/feature2d.cpp).
#include <string>
#include <string_view>
#include <vector>

namespace aief::option_table {

// The name of `known` at the smallest edit distance from `name` (insertions, deletions,
// substitutions, case ignored), the first of equals; empty when none is within a third of the
// name's length (no suggestion is better than a wrong one).
std::string nearest_name(std::string_view name, const std::vector<std::string_view>& known);

}  // namespace aief::option_table

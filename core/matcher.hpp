#pragma once
// match_descriptors with the Hamming kernel of a given table (the public function uses the
// best the CPU runs). Rows of the distance matrix run in parallel when `scheduler` is given.
#include <optional>
#include <string_view>

#include "aief/match.hpp"
#include "core/kernel_table.hpp"

namespace aief {

std::vector<Match> match_descriptors(const std::vector<Descriptor>& a,
                                     const std::vector<Descriptor>& b, const MatchOptions& options,
                                     const KernelTable& kernels);

// The matcher options a front end was given (the CLI's --matcher / --ratio, Python's matcher= /
// ratio=), validated: a ratio goes with the ratio matcher only, where another kind would ignore
// it, so it is refused, named as the front end names it. Throws aief::Error.
MatchOptions match_options_given(std::optional<std::string_view> matcher,
                                 std::optional<double> ratio, std::string_view ratio_named,
                                 std::string_view matcher_named);

}  // namespace aief

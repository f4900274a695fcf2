#pragma once
// The one dispatch point (STYLE.md "One kernel, three places, one signature").
#include <vector>

#include "aief/options.hpp"
#include "core/kernel_table.hpp"

namespace aief {

// Kernel sets this binary has compiled in and this CPU can run, scalar first, best last.
std::vector<KernelSet> available_kernel_sets();

// The best available set (what KernelSet::auto_select means).
KernelSet best_kernel_set();

// The table of `set` (auto_select resolves to best_kernel_set()). Throws aief::Error when
// the CPU or the build lacks it.
const KernelTable& kernel_table(KernelSet set);

}  // namespace aief

#pragma once
// The one dispatch point: the only code that asks what the CPU runs (docs/design.md).
#include <vector>

#include "aief/options.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

// Kernel sets this binary has compiled in and this CPU can run, scalar first, best last.
std::vector<KernelSet> available_kernel_sets();

// The best available set.
KernelSet best_kernel_set();

// The environment variable that decides what KernelSet::auto_select (every front end's default)
// stands for, so a host program's kernels can be forced without changing its code, as
// libjpeg-turbo's JSIMD_FORCENONE does: AIEF_KERNELS=scalar, sse4.2, avx2, avx512, neon64 or auto.
// An explicit set in ExtractorOptions::kernels (--kernels) is not overridden.
inline constexpr const char* kKernelsEnvironmentVariable = "AIEF_KERNELS";

// What KernelSet::auto_select stands for: the set AIEF_KERNELS names when it is set and not
// empty ("auto" meaning best_kernel_set()), otherwise best_kernel_set(). Throws aief::Error,
// naming the variable and its value, when the value is not a kernel set or this CPU or build
// cannot run that set: a forced set that silently did not apply would defeat the purpose.
KernelSet default_kernel_set();

// kernel_table(set), the table of a set, is declared in core/kernels/kernel_table.hpp and defined
// in simd/kernels.cpp.

}  // namespace aief

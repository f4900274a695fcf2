// The sse4.2 kernel table. Compiled with only this instruction set's flags (simd/CMakeLists.txt).
#include "simd/make_kernel_table.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

KernelTable kernel_table() { return make_kernel_table<xsimd::sse4_2>(KernelSet::sse4_2); }

AIEF_SIMD_NAMESPACE_END

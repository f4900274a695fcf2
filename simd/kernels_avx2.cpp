// The avx2 kernel table. Compiled with only this instruction set's flags (simd/CMakeLists.txt).
#include "simd/make_kernel_table.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

KernelTable kernel_table() { return make_kernel_table<xsimd::avx2>(KernelSet::avx2); }

AIEF_SIMD_NAMESPACE_END

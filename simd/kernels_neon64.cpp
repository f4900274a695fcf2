// The neon64 kernel table (AArch64 Advanced SIMD, 128-bit). NEON is part of the AArch64 base
// architecture, so this unit needs no extra flags and the table runs on every aarch64 CPU.
#include "simd/make_kernel_table.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

KernelTable kernel_table() { return make_kernel_table<xsimd::neon64>(KernelSet::neon64); }

AIEF_SIMD_NAMESPACE_END

#pragma once
// Helpers shared by the xsimd kernels. Everything here is a template on the xsimd arch, so an
// instantiation compiled with AVX2 flags is its own symbol and can never be linked into the
// baseline path (docs/design.md §13).
//
// The few operations xsimd 8.1 lacks are written per instruction-set family, each in its own
// header with the same two functions:
//   lane_bits(b)    one bit per byte lane (lane i -> bit i) of a byte comparison (a movemask)
//   any_nonzero(v)  whether any byte lane of v is non-zero
#include <cstdint>

#include <xsimd/xsimd.hpp>

// Each kernel set's unit (simd/kernels_<set>.cpp) is compiled with its own instruction-set flags,
// and simd/CMakeLists.txt names the set in AIEF_SIMD_SET: the set's kernels and its table live in
// the namespace aief::simd::<set> (aief::simd::avx2, ...), one per set. Without it, the 256-bit
// kernels the AVX-512 unit instantiates (compiled with AVX-512 flags) and those of the AVX2 unit
// would be one symbol, and the linker could hand the AVX2 table code that runs only on AVX-512
// CPUs.
#ifndef AIEF_SIMD_SET
#error "simd kernels are compiled only in the per-instruction-set units, simd/kernels_<set>.cpp"
#endif

// Every simd/ header opens and closes that namespace with these, written once here.
#define AIEF_SIMD_NAMESPACE_BEGIN namespace aief::simd::AIEF_SIMD_SET {
#define AIEF_SIMD_NAMESPACE_END }

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
using U8 = xsimd::batch<std::uint8_t, Arch>;

AIEF_SIMD_NAMESPACE_END

#if defined(__aarch64__)
#include "simd/simd_support_neon.hpp"
#else
#include "simd/simd_support_x86.hpp"
#endif

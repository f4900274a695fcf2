// The Hamming kernel of the sweep matcher with AVX-512 VPOPCNTDQ (one popcount per 32-bit lane).
// Not every AVX-512BW CPU has the extension (Skylake-X lacks it), so it is compiled apart, with
// the avx512 set's flags plus -mavx512vpopcntdq (simd/CMakeLists.txt), and kernels.cpp puts it
// into the avx512 table only when the CPU reports it; without it that table keeps the AVX2 form.
#include "simd/hamming_256_blocked/x86_avx512vpopcntdq.hpp"
#include "simd/make_kernel_table.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

KernelEntry<decltype(&hamming_256_blocked_scalar)> hamming_256_blocked() {
  return {&hamming_256_blocked_vpopcntdq, variant<xsimd::avx512bw>()};
}

AIEF_SIMD_NAMESPACE_END

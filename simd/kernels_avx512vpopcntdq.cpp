// The Hamming kernel of the sweep matcher with AVX-512 VPOPCNTDQ (one popcount per 32-bit lane).
// Not every AVX-512BW CPU has the extension (Skylake-X lacks it), so it is compiled apart, with
// the avx512 set's flags plus -mavx512vpopcntdq (simd/CMakeLists.txt), and kernels.cpp puts it
// into the avx512 table only when the CPU reports it; without it that table keeps the AVX2 form.
#include "core/kernels/kernel_table.hpp"
#include "simd/hamming_256_blocked_x86.hpp"

namespace aief::simd_avx512vpopcntdq {

KernelEntry<decltype(&hamming_256_blocked_scalar)> hamming_256_blocked() {
  return {&simd::hamming_256_blocked_vpopcntdq, "avx512vpopcntdq 512-bit"};
}

}  // namespace aief::simd_avx512vpopcntdq

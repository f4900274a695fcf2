// The avx2 kernel table. Compiled with only this instruction set's flags (simd/CMakeLists.txt).
#include "simd/make_kernel_table.hpp"

namespace aief::simd_avx2 {

KernelTable kernel_table() {
  return simd::make_kernel_table<xsimd::avx2>(KernelSet::avx2, "avx2", "avx2 256-bit");
}

}  // namespace aief::simd_avx2

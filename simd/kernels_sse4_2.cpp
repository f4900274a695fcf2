// The sse4.2 kernel table. Compiled with only this instruction set's flags (simd/CMakeLists.txt).
#include "simd/make_kernel_table.hpp"

namespace aief::simd_sse4_2 {

KernelTable kernel_table() {
  return simd::make_kernel_table<xsimd::sse4_2>(KernelSet::sse4_2, "sse4.2", "sse4.2 128-bit");
}

}  // namespace aief::simd_sse4_2

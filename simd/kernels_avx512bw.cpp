// The avx512 kernel table. Compiled with only this instruction set's flags (simd/CMakeLists.txt).
#include "simd/kernel_table_simd.hpp"

namespace aief::simd_avx512bw {

KernelTable kernel_table() { return simd::make_kernel_table<xsimd::avx512bw>(KernelSet::avx512bw, "avx512"); }

}  // namespace aief::simd_avx512bw

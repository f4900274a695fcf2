// The avx512 kernel table. Compiled with only the AVX-512 (F, CD, DQ, BW) flags
// (simd/CMakeLists.txt), so the compiler may use EVEX encodings, 32 vector registers and mask
// registers, but the kernels are instantiated at 256-bit width: measured on this project's
// 2-core Xeon, 512-bit FAST is faster alone (fast9/avx512 1.33 ms vs avx2 1.94 ms over the graf
// pyramid) but makes the whole extract slower (entropy + FAST stage 5.3 ms vs 3.4 ms), the cost
// of the core's 512-bit frequency licence on the scalar code around it. See bench/RESULTS.md.
#include "simd/kernel_table_simd.hpp"

namespace aief::simd_avx512bw {

KernelTable kernel_table() { return simd::make_kernel_table<xsimd::avx2>(KernelSet::avx512bw, "avx512"); }

}  // namespace aief::simd_avx512bw

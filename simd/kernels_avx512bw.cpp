// The avx512 kernel table. Compiled with only the AVX-512 (F, CD, DQ, BW) flags
// (simd/CMakeLists.txt). FAST-9 scores and local maxima run 64 pixels per vector (one bit word
// per vector for the maxima); the pyramid resize uses vpermw on 512-bit rows and the 7x7 blur
// runs 32 columns a step (both measured faster in CPU samples of an extract); the other kernels
// are instantiated at 256-bit width (still EVEX-encoded, 32 registers): on this project's 2-core
// EPYC their 512-bit forms measured no faster, and 512-bit code around scalar code can cost a
// frequency licence on Intel parts. Measured end to end on graf: entropy + FAST stage 3.08 ms
// with this table vs 3.17 ms with avx2 (median of 31, same run). See bench/RESULTS.md.
#include "simd/make_kernel_table.hpp"
#include "simd/resize_bilinear_rows_x86_avx512.hpp"

namespace aief::simd_avx512bw {

KernelTable kernel_table() {
  KernelTable table =
      simd::make_kernel_table<xsimd::avx2>(KernelSet::avx512bw, "avx512", "avx512bw 256-bit");
  constexpr const char* k512 = "avx512bw 512-bit";
  table.fast9_scores_row = {&simd::fast9_scores_row<xsimd::avx512bw>, k512};
  table.fast9_local_maxima_bits = {&simd::fast9_local_maxima_bits<xsimd::avx512bw>, k512};
  table.positions_within_bounds = {&simd::positions_within_bounds<xsimd::avx512bw>,
                                   k512};  // one mask compare per 32
  table.rbrief_describe = {&simd::rbrief_describe<xsimd::avx512bw>, k512};  // 16 offsets a step
  table.resize_bilinear_rows = {&simd::resize_bilinear_rows_avx512<xsimd::avx512bw>,
                                k512};  // vpermw: ~15 instructions per 16 outputs
  table.gaussian7_rows = {&simd::gaussian7_rows<xsimd::avx512bw>,
                          k512};  // 32 columns a step, masked last step
  return table;
}

}  // namespace aief::simd_avx512bw

// The avx512 kernel table. Compiled with only the AVX-512 (F, CD, DQ, BW) flags
// (simd/CMakeLists.txt). FAST-9 scores and local maxima run 64 pixels per vector (one bit word
// per vector for the maxima); the pyramid resize uses vpermw on 512-bit rows and the 7x7 blur
// runs 32 columns a step (both measured faster in CPU samples of an extract); the other kernels
// are instantiated at 256-bit width (still EVEX-encoded, 32 registers): on this project's 2-core
// EPYC their 512-bit forms measured no faster, and 512-bit code around scalar code can cost a
// frequency licence on Intel parts. Measured end to end on graf: entropy + FAST stage 3.08 ms
// with this table vs 3.17 ms with avx2 (median of 31, same run). See bench/RESULTS.md.
#include "simd/make_kernel_table.hpp"
#include "simd/resize_bilinear_rows/x86_avx512bw.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

KernelTable kernel_table() {
  KernelTable table = make_kernel_table<xsimd::avx2>(KernelSet::avx512bw);
  using Wide = xsimd::avx512bw;
  const char* const wide = variant<Wide>();
  table.fast9_scores_row = {&fast9_scores_row<Wide>, wide};
  table.fast9_local_maxima_bits = {&fast9_local_maxima_bits<Wide>, wide};
  table.positions_within_bounds = {&positions_within_bounds<Wide>,
                                   wide};                  // one mask compare per 32
  table.rbrief_describe = {&rbrief_describe<Wide>, wide};  // 16 offsets a step
  table.resize_bilinear_rows = {&resize_bilinear_rows_avx512<Wide>,
                                wide};                   // vpermw: ~15 instructions per 16 outputs
  table.gaussian7_rows = {&gaussian7_rows<Wide>, wide};  // 32 columns a step, masked last step
  return table;
}

AIEF_SIMD_NAMESPACE_END

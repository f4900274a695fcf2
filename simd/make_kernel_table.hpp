#pragma once
// The kernel table of one xsimd arch: included only by the per-set units (kernels_<set>.cpp),
// each compiled with that set's flags alone. File suffixes say what a kernel file is:
// *_portable.hpp is written once for every set (xsimd batches, or a register layer per family),
// *_x86.hpp holds SSE4.2 / AVX2 / AVX-512 intrinsics, *_neon.hpp AArch64 NEON intrinsics.
#include "core/kernel_table.hpp"
#include "simd/fast9_portable.hpp"
#include "simd/gaussian_blur_portable.hpp"
#include "simd/histogram_portable.hpp"
#include "simd/rbrief_portable.hpp"
#if defined(__aarch64__)
#include "simd/hamming_blocked_neon.hpp"
#include "simd/hamming_neon.hpp"
#include "simd/orientation_neon.hpp"
#include "simd/pyramid_resize_neon.hpp"
#else
#include "simd/bound_filter_x86.hpp"
#include "simd/hamming_blocked_x86.hpp"
#include "simd/hamming_x86.hpp"
#include "simd/orientation_x86.hpp"
#include "simd/pyramid_resize_x86.hpp"
#endif

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

// Every kernel of the table at the width of Arch; `variant` names that code in
// `aief --print-kernels` (e.g. "avx2 256-bit").
template <class Arch>
KernelTable make_kernel_table(KernelSet set, const char* name, const char* variant) {
  KernelTable table;
  table.set = set;
  table.name = name;
  table.resize_bilinear_rows = {&resize_bilinear_rows<Arch>, variant};
  table.gaussian7_rows = {&gaussian7_rows<Arch>, variant};
  table.accumulate_histogram = {&accumulate_histogram<Arch>, variant};
  table.fast9_scores_row = {&fast9_scores_row<Arch>, variant};
  table.fast9_local_maxima_bits = {&fast9_local_maxima_bits<Arch>, variant};
  table.ic_moments = {&ic_moments<Arch>, variant};
  table.rbrief_describe = {&rbrief_describe<Arch>, variant};
  table.hamming_256_many = {&hamming_256_many<Arch>, variant};
  table.hamming_256_blocked = {&hamming_256_blocked<Arch>, variant};
#if !defined(__aarch64__)
  table.positions_within_bounds = {&positions_within_bounds<Arch>, variant};
#endif  // NEON keeps the scalar filter: no NEON version yet
  return table;
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

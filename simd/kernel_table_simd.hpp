#pragma once
// The kernel table of one xsimd arch: included only by the per-arch translation units
// (kernels_<arch>.cpp), each compiled with that arch's flags alone.
#include "core/kernel_table.hpp"
#include "simd/bound_filter_simd.hpp"
#include "simd/fast9_simd.hpp"
#include "simd/gaussian_blur_simd.hpp"
#include "simd/histogram_simd.hpp"
#include "simd/rbrief_simd.hpp"
// Kernels written with one instruction-set family's intrinsics, each family in its own files.
#if defined(__aarch64__)
#include "simd/hamming_blocked_neon.hpp"
#include "simd/hamming_neon.hpp"
#include "simd/orientation_neon.hpp"
#include "simd/pyramid_resize_neon.hpp"
#else
#include "simd/hamming_blocked_simd.hpp"
#include "simd/hamming_simd.hpp"
#include "simd/orientation_simd.hpp"
#include "simd/pyramid_resize_simd.hpp"
#endif

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

// Every kernel of the table, at the width of Arch.
template <class Arch>
KernelTable make_kernel_table(KernelSet set, const char* name) {
  KernelTable table;
  table.set = set;
  table.name = name;
  table.fast9_scores_row = &fast9_scores_row<Arch>;
  table.fast9_local_maxima_bits = &fast9_local_maxima_bits<Arch>;
  table.hamming_256_many = &hamming_256_many<Arch>;
  table.hamming_256_blocked = &hamming_256_blocked<Arch>;
  table.positions_within_bounds = &positions_within_bounds<Arch>;
  table.gaussian7_rows = &gaussian7_rows<Arch>;
  table.ic_moments = &ic_moments<Arch>;
  table.rbrief_describe = &rbrief_describe<Arch>;
  table.resize_bilinear_rows = &resize_bilinear_rows<Arch>;
  table.accumulate_histogram = &accumulate_histogram<Arch>;
  return table;
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

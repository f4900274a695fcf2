#pragma once
// The kernel table of one xsimd arch: included only by the per-set units (kernels_<set>.cpp),
// each compiled with that set's flags alone. File suffixes say what a kernel file is:
// *_portable.hpp is written once for every set (xsimd batches, or a register layer per family),
// *_x86.hpp holds SSE4.2 / AVX2 / AVX-512 intrinsics, *_neon.hpp AArch64 NEON intrinsics.
#include <cstddef>

#include "core/kernels/kernel_table.hpp"
#include "simd/binomial_blur_portable.hpp"
#include "simd/block_entropy_portable.hpp"
#include "simd/fast9_portable.hpp"
#include "simd/gaussian_blur_portable.hpp"
#include "simd/rbrief_portable.hpp"
#include "simd/unsharp_mask_portable.hpp"
#if defined(__aarch64__)
#include "simd/bound_filter_neon.hpp"
#include "simd/hamming_blocked_neon.hpp"
#include "simd/hamming_neon.hpp"
#include "simd/orientation_neon.hpp"
#include "simd/pyramid_resize_neon.hpp"
#include "simd/pyramid_resize_opencv_neon.hpp"
#else
#include "simd/bound_filter_x86.hpp"
#include "simd/hamming_blocked_x86.hpp"
#include "simd/hamming_x86.hpp"
#include "simd/orientation_x86.hpp"
#include "simd/pyramid_resize_opencv_x86.hpp"
#include "simd/pyramid_resize_x86.hpp"
#endif

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

// One entry from the set's kernel: `kernel` is the function template's instance for Arch.
template <class Entry>
void set_kernel_entry(Entry& entry, typename Entry::Function kernel, const char* variant) {
  entry = {kernel, variant};
}
// A family that keeps the scalar reference for a kernel says so with a null constant of the
// kernel's name (simd/bound_filter_neon.hpp): the entry stays scalar, and --print-kernels says so.
template <class Entry>
void set_kernel_entry(Entry&, std::nullptr_t, const char*) {}

// Every kernel of the table at the width of Arch; `variant` names that code in
// `aief --print-kernels` (e.g. "avx2 256-bit"). The entries are made from the one kernel list
// (AIEF_FOR_EACH_KERNEL): a kernel listed there without a `name<Arch>` for this family (or the
// null constant above) does not compile, so none silently stays scalar.
template <class Arch>
KernelTable make_kernel_table(KernelSet set, const char* name, const char* variant) {
  KernelTable table;
  table.set = set;
  table.name = name;
#define AIEF_SET_KERNEL_ENTRY(kernel) set_kernel_entry(table.kernel, kernel<Arch>, variant);
  AIEF_FOR_EACH_KERNEL(AIEF_SET_KERNEL_ENTRY)
#undef AIEF_SET_KERNEL_ENTRY
  return table;
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

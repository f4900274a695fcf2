#pragma once
// The pixel kernels of one instruction set, as function pointers. Filled once, when an
// extractor is built, by simd/kernels.cpp (the only place that looks at the CPU). Every entry
// has the contract of its scalar reference in core/ and must give the same bytes.
#include <string_view>
#include <type_traits>

#include "aief/options.hpp"
#include "core/kernels/binomial_blur.hpp"
#include "core/kernels/block_entropy.hpp"
#include "core/kernels/bound_filter.hpp"
#include "core/kernels/fast9.hpp"
#include "core/kernels/gaussian_blur.hpp"
#include "core/kernels/hamming.hpp"
#include "core/kernels/hamming_blocked.hpp"
#include "core/kernels/orientation.hpp"
#include "core/kernels/pyramid_resize.hpp"
#include "core/kernels/pyramid_resize_opencv.hpp"
#include "core/kernels/rbrief.hpp"
#include "core/kernels/unsharp_mask.hpp"

// The one list of kernels, in table order: X(name) for a kernel whose scalar reference is
// name##_scalar. KernelTable's entries, the bit-exact validation (simd/kernel_validation.cpp),
// the per-set benchmarks (bench/bench_kernel_sets.cpp) and `aief --print-kernels` are all made
// from it, so a kernel added here and missing from any of them does not compile
// (CONTRIBUTING.md, "Adding a kernel").
#define AIEF_FOR_EACH_KERNEL(X) \
  X(resize_bilinear_rows)       \
  X(resize_opencv_linear_rows)  \
  X(gaussian7_rows)             \
  X(accumulate_histogram)       \
  X(fast9_scores_row)           \
  X(fast9_local_maxima_bits)    \
  X(ic_moments)                 \
  X(rbrief_describe)            \
  X(hamming_256_many)           \
  X(hamming_256_blocked)        \
  X(positions_within_bounds)    \
  X(unsharp_row)                \
  X(binomial5_row)

namespace aief {

// One entry of a table: the function and which code it is, e.g. "avx512bw 512-bit" for the
// AVX-512 table's own FAST kernel beside "avx512bw 256-bit" for one it shares with AVX2 (compiled
// with AVX-512 flags). Called like the function itself, with the function's own parameter types.
template <class Function>
struct KernelEntry;

template <class Result, class... Params>
struct KernelEntry<Result (*)(Params...)> {
  using Function = Result (*)(Params...);
  Function run;
  const char* variant;

  KernelEntry(Function function, const char* variant_name) : run(function), variant(variant_name) {}
  // Any callable that converts to the function pointer (a test's counting lambda).
  template <class Callable, class = std::enable_if_t<std::is_convertible_v<Callable, Function>>>
  KernelEntry(Callable callable) : run(callable), variant("custom") {}

  Result operator()(Params... params) const { return run(params...); }
};

struct KernelTable {
  KernelSet set = KernelSet::scalar;
  const char* name = "scalar";
#define AIEF_KERNEL_ENTRY(kernel) \
  KernelEntry<decltype(&kernel##_scalar)> kernel{&kernel##_scalar, "scalar"};
  AIEF_FOR_EACH_KERNEL(AIEF_KERNEL_ENTRY)
#undef AIEF_KERNEL_ENTRY
};

// The kernels' names, in table order.
inline constexpr const char* kKernelNames[] = {
#define AIEF_KERNEL_NAME(kernel) #kernel,
    AIEF_FOR_EACH_KERNEL(AIEF_KERNEL_NAME)
#undef AIEF_KERNEL_NAME
};
inline constexpr int kKernelCount = static_cast<int>(sizeof kKernelNames / sizeof kKernelNames[0]);

// `name` when it is a kernel of the list; used as a constant (constexpr), a name not in the list
// does not compile. Benchmarks and reports name kernels through it.
constexpr const char* listed_kernel(std::string_view name) {
  for (const char* kernel : kKernelNames)
    if (name == kernel) return kernel;
  throw "not a kernel of AIEF_FOR_EACH_KERNEL";
}

// The table of `set` (auto_select resolves to default_kernel_set(), simd/kernels.hpp). Throws
// aief::Error when the CPU or the build lacks it. Declared here for core/, defined by the one
// dispatch point, simd/kernels.cpp: core/ names no simd/ header.
const KernelTable& kernel_table(KernelSet set);

// Which code the table runs for the kernel at `index` (into kKernelNames).
inline const char* kernel_variant(const KernelTable& table, int index) {
  int at = 0;
#define AIEF_KERNEL_VARIANT(kernel) \
  if (at++ == index) return table.kernel.variant;
  AIEF_FOR_EACH_KERNEL(AIEF_KERNEL_VARIANT)
#undef AIEF_KERNEL_VARIANT
  return "";
}

}  // namespace aief

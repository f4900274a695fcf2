#include "simd/kernels.hpp"

#include <cstdlib>
#include <string>

#include "aief/error.hpp"

// Each set's table, made in its own unit (simd/kernels_<set>.cpp) in the namespace of its set.
#if AIEF_HAVE_X86_SIMD
namespace aief::simd::sse4_2 {
KernelTable kernel_table();
}
namespace aief::simd::avx2 {
KernelTable kernel_table();
}
namespace aief::simd::avx512bw {
KernelTable kernel_table();
}
namespace aief::simd::avx512vpopcntdq {
KernelEntry<decltype(&aief::hamming_256_blocked_scalar)> hamming_256_blocked();
}
#endif
#if AIEF_HAVE_NEON64
namespace aief::simd::neon64 {
KernelTable kernel_table();
}
#endif

namespace aief {

namespace {

// What this CPU runs, asked once (the only place in the library that looks at the CPU).
struct CpuKernels {
  KernelTable scalar{};
#if AIEF_HAVE_X86_SIMD
  // A table is built only when the CPU runs its instruction set: building it executes code
  // compiled with that set's flags.
  KernelTable sse4_2, avx2, avx512bw;
  bool has_sse4_2 = false, has_avx2 = false, has_avx512bw = false;
  CpuKernels() {
    __builtin_cpu_init();
    has_sse4_2 = __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt");
    has_avx2 = has_sse4_2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
               __builtin_cpu_supports("bmi2");
    has_avx512bw = has_avx2 && __builtin_cpu_supports("avx512f") &&
                   __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                   __builtin_cpu_supports("avx512bw");
    if (has_sse4_2) sse4_2 = simd::sse4_2::kernel_table();
    if (has_avx2) avx2 = simd::avx2::kernel_table();
    if (has_avx512bw) avx512bw = simd::avx512bw::kernel_table();
    if (has_avx512bw && __builtin_cpu_supports("avx512vpopcntdq"))
      avx512bw.hamming_256_blocked = simd::avx512vpopcntdq::hamming_256_blocked();
  }
#endif
#if AIEF_HAVE_NEON64
  // NEON is in every AArch64 CPU (base architecture): nothing to ask.
  KernelTable neon64 = simd::neon64::kernel_table();
#endif
};

const CpuKernels& cpu_kernels() {
  static const CpuKernels kernels;
  return kernels;
}

}  // namespace

std::vector<KernelSet> available_kernel_sets() {
  std::vector<KernelSet> sets = {KernelSet::scalar};
#if AIEF_HAVE_X86_SIMD
  const CpuKernels& cpu = cpu_kernels();
  if (cpu.has_sse4_2) sets.push_back(KernelSet::sse4_2);
  if (cpu.has_avx2) sets.push_back(KernelSet::avx2);
  if (cpu.has_avx512bw) sets.push_back(KernelSet::avx512bw);
#endif
#if AIEF_HAVE_NEON64
  sets.push_back(KernelSet::neon64);
#endif
  return sets;
}

KernelSet best_kernel_set() { return available_kernel_sets().back(); }

std::string available_kernel_set_names() {
  std::string names;
  for (KernelSet set : available_kernel_sets())
    names += (names.empty() ? "" : ", ") + std::string(to_string(set));
  return names;
}

KernelSet default_kernel_set() {
  const char* forced = std::getenv(kKernelsEnvironmentVariable);
  if (forced == nullptr || *forced == '\0') return best_kernel_set();
  const std::string where = std::string(kKernelsEnvironmentVariable) + "=" + forced + ": ";
  KernelSet set;
  try {
    set = parse_kernel_set(forced);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  if (set == KernelSet::auto_select) return best_kernel_set();
  for (KernelSet available : available_kernel_sets())
    if (available == set) return set;
  throw Error(where + "this CPU or build cannot run kernel set " + std::string(to_string(set)) +
              " (it runs " + available_kernel_set_names() + ")");
}

const KernelTable& kernel_table(KernelSet set) {
  if (set == KernelSet::auto_select) set = default_kernel_set();
  const CpuKernels& cpu = cpu_kernels();
  if (set == KernelSet::scalar) return cpu.scalar;
#if AIEF_HAVE_X86_SIMD
  if (set == KernelSet::sse4_2 && cpu.has_sse4_2) return cpu.sse4_2;
  if (set == KernelSet::avx2 && cpu.has_avx2) return cpu.avx2;
  if (set == KernelSet::avx512bw && cpu.has_avx512bw) return cpu.avx512bw;
#endif
#if AIEF_HAVE_NEON64
  if (set == KernelSet::neon64) return cpu.neon64;
#endif
  throw Error("kernel set " + std::string(to_string(set)) +
              " is not available on this CPU or build (it runs " + available_kernel_set_names() +
              ")");
}

}  // namespace aief

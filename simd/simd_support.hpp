#pragma once
// Helpers shared by the xsimd kernels. Everything here is a template on the xsimd arch, so an
// instantiation compiled with AVX2 flags is its own symbol and can never be linked into the
// baseline path (STYLE.md "One kernel, three places, one signature").
#include <cstdint>
#include <type_traits>

#include <immintrin.h>
#include <xsimd/xsimd.hpp>

// Each kernel unit (simd/kernels_<set>.cpp) is compiled with its own instruction-set flags, and
// simd/CMakeLists.txt names it in AIEF_SIMD_TARGET: every kernel lives in an inline namespace of
// that name. Without it, the 256-bit kernels the AVX-512 unit instantiates (compiled with
// AVX-512 flags) and those of the AVX2 unit would be one symbol, and the linker could hand the
// AVX2 table code that runs only on AVX-512 CPUs.
#ifndef AIEF_SIMD_TARGET
#error "simd kernels are compiled only in the per-instruction-set units, simd/kernels_<set>.cpp"
#endif

namespace aief::simd {
inline namespace AIEF_SIMD_TARGET {

template <class Arch>
using U8 = xsimd::batch<std::uint8_t, Arch>;

// One bit per byte lane (lane i -> bit i), from a byte comparison: the movemask xsimd 8.1
// does not expose.
template <class Arch>
inline std::uint64_t lane_bits(const xsimd::batch_bool<std::uint8_t, Arch>& b) {
  if constexpr (std::is_base_of_v<xsimd::avx512bw, Arch>) {
    return static_cast<std::uint64_t>(static_cast<__mmask64>(b));
  } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    return static_cast<std::uint32_t>(_mm256_movemask_epi8(static_cast<__m256i>(b)));
  } else {
    return static_cast<std::uint32_t>(_mm_movemask_epi8(static_cast<__m128i>(b)));
  }
}

// Whether any byte lane is non-zero: one vptest (SSE4.1, AVX2) or vptestmb (AVX-512BW).
template <class Arch>
inline bool any_nonzero(const U8<Arch>& v) {
  if constexpr (std::is_base_of_v<xsimd::avx512bw, Arch>) {
    const __m512i x = v;
    return _mm512_test_epi8_mask(x, x) != 0;
  } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
    const __m256i x = v;
    return !_mm256_testz_si256(x, x);
  } else {
    const __m128i x = v;
    return !_mm_testz_si128(x, x);
  }
}

}  // namespace AIEF_SIMD_TARGET
}  // namespace aief::simd

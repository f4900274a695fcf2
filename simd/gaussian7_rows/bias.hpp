#pragma once
// The one bias of the vectorised 7x7 Gaussian (simd/gaussian7_rows/portable.hpp, which derives
// it), shared by its register layers (simd/gaussian7_rows/registers_x86.hpp,
// simd/gaussian7_rows/registers_neon.hpp).
#include <cstdint>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN
namespace gaussian7_rows_detail {

// Vertical sums v (0..65280) are stored as the int16 v - kBias (|v - kBias| <= 32640), so the
// horizontal pmaddwd sum is S - 256 kBias = S + 2^15 - 2^23: the rounding term comes for free.
constexpr std::int16_t kBias = 32640;

}  // namespace gaussian7_rows_detail
AIEF_SIMD_NAMESPACE_END

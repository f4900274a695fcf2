#pragma once
// One integral image row, vectorised: the contract of core/kernels/integral_image_row.hpp, the
// same entries (integer adds only; uint32 wraps alike in any order).
//
// A step takes kPixels pixels: their prefix sum within a vector in uint16 lanes (eight pixels sum
// to at most 2040), widened to uint32, plus the carry of the row so far (the last sum broadcast
// to every lane) and the row above. The steps are per instruction-set family
// (the register layer integral_image_row_detail::Registers<Arch>,
// simd/integral_image_row/registers_x86.hpp and registers_neon.hpp); the tail is the reference's
// loop from their carry.
#include <cstdint>

#include "core/kernels/integral_image_row.hpp"
#include "simd/simd_support.hpp"
#if defined(__aarch64__)
#include "simd/integral_image_row/registers_neon.hpp"
#else
#include "simd/integral_image_row/registers_x86.hpp"
#endif

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void integral_image_row(const std::uint8_t* pixels, int width, const std::uint32_t* above,
                        std::uint32_t* out) {
  using Registers = integral_image_row_detail::Registers<Arch>;
  out[0] = 0;
  typename Registers::Carry carry{};  // zero in every lane
  int x = 0;
  for (; x + Registers::kPixels <= width; x += Registers::kPixels) {
    carry = Registers::step(pixels + x, above + x + 1, out + x + 1, carry);
  }
  integral_image_row_from(pixels, x, Registers::row_sum(carry), width, above, out);
}

AIEF_SIMD_NAMESPACE_END

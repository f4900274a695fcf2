#pragma once
// Hamming distances of one 256-bit descriptor to many on AArch64 NEON: the contract of
// core/kernels/hamming_256_many.hpp. A descriptor is two 128-bit registers: XOR, byte popcount
// (cnt), the two halves' counts added per byte (<= 16) and summed across with one widening add
// (uaddlv).
#include <cstdint>

#include <arm_neon.h>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
void hamming_256_many(const std::uint8_t* query, const std::uint8_t* train, int n_train,
                      std::uint16_t* distances) {
  const uint8x16_t q0 = vld1q_u8(query), q1 = vld1q_u8(query + 16);
  for (int j = 0; j < n_train; ++j) {
    const std::uint8_t* t = train + 32 * j;
    const uint8x16_t counts =
        vaddq_u8(vcntq_u8(veorq_u8(q0, vld1q_u8(t))), vcntq_u8(veorq_u8(q1, vld1q_u8(t + 16))));
    distances[j] = vaddlvq_u8(counts);
  }
}

AIEF_SIMD_NAMESPACE_END

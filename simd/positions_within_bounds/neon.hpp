#pragma once
// NEON has no version of the bound filter (core/kernels/positions_within_bounds.hpp) yet: the
// neon64 table keeps positions_within_bounds_scalar, and `aief --print-kernels` names it "scalar".
// The null constant is how a family says so to simd/make_kernel_table.hpp, whose entries are made
// from the kernel list; a NEON version replaces it with `template <class Arch> ... function`.
#include <cstddef>

#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

template <class Arch>
constexpr std::nullptr_t positions_within_bounds = nullptr;

AIEF_SIMD_NAMESPACE_END

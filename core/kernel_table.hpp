#pragma once
// The pixel kernels of one instruction set, as function pointers. Filled once, when an
// extractor is built, by simd/kernels.cpp (the only place that looks at the CPU). Every entry
// has the contract of its scalar reference in core/ and must give the same bytes.
#include "aief/options.hpp"
#include "core/block_entropy.hpp"
#include "core/bound_filter.hpp"
#include "core/fast9.hpp"
#include "core/gaussian_blur.hpp"
#include "core/hamming.hpp"
#include "core/hamming_blocked.hpp"
#include "core/orientation.hpp"
#include "core/pyramid_resize.hpp"
#include "core/rbrief.hpp"

namespace aief {

struct KernelTable {
  KernelSet set = KernelSet::scalar;
  const char* name = "scalar";
  decltype(&resize_bilinear_rows_scalar) resize_bilinear_rows = resize_bilinear_rows_scalar;
  decltype(&gaussian7_rows_scalar) gaussian7_rows = gaussian7_rows_scalar;
  decltype(&accumulate_histogram_scalar) accumulate_histogram = accumulate_histogram_scalar;
  decltype(&fast9_scores_row_scalar) fast9_scores_row = fast9_scores_row_scalar;
  decltype(&fast9_local_maxima_bits_scalar) fast9_local_maxima_bits = fast9_local_maxima_bits_scalar;
  decltype(&ic_moments_scalar) ic_moments = ic_moments_scalar;
  decltype(&rbrief_describe_scalar) rbrief_describe = rbrief_describe_scalar;
  decltype(&hamming_256_many_scalar) hamming_256_many = hamming_256_many_scalar;
  decltype(&hamming_256_blocked_scalar) hamming_256_blocked = hamming_256_blocked_scalar;
  decltype(&positions_within_bounds_scalar) positions_within_bounds = positions_within_bounds_scalar;
};

}  // namespace aief

#pragma once
// adapt() with the kernel table given, so tests can count what the sweep computes.
#include "aief/adapt.hpp"
#include "core/kernel_table.hpp"

namespace aief {

AdaptResult adapt_with_kernels(ImageView a, ImageView b, const ExtractorOptions& options,
                               const SweepOptions& sweep, const KernelTable& kernels);

}  // namespace aief

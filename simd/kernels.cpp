#include "simd/kernels.hpp"

#include <string>

#include "aief/error.hpp"

namespace aief {

namespace {
const KernelTable kScalarTable{};
}  // namespace

std::vector<KernelSet> available_kernel_sets() { return {KernelSet::scalar}; }

KernelSet best_kernel_set() { return available_kernel_sets().back(); }

const KernelTable& kernel_table(KernelSet set) {
  if (set == KernelSet::auto_select) set = best_kernel_set();
  if (set == KernelSet::scalar) return kScalarTable;
  throw Error("kernel set " + std::string(to_string(set)) + " is not available on this CPU or build");
}

}  // namespace aief

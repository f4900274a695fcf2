#pragma once
// Eq. 9 of the paper: which blocks of a level a threshold F keeps (docs/design.md §3).
#include <cstddef>
#include <vector>

namespace aief {

// Eq. 9 on one level: block b is kept at F when its entropy is above F; with entropy off
// (entropy_bits == nullptr) every block is kept.
struct BlockMask {
  const std::vector<double>* entropy_bits = nullptr;
  double threshold = 0;

  bool kept(int b) const {
    return entropy_bits == nullptr || (*entropy_bits)[static_cast<std::size_t>(b)] > threshold;
  }
};

}  // namespace aief

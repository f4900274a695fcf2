#pragma once
// FNV-1a (64-bit) over every output byte a user can see: pins outputs in the tests
// (test_paper_mode) and compares builds (aief_pipeline_hash, x86-64 against aarch64). Floats are
// hashed bit for bit; both targets are little-endian IEEE-754.
#include <cstddef>
#include <cstdint>

#include "aief/features.hpp"

namespace aief::test {

class Fnv1a {
 public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ull;
  }
  template <class T>
  void add_value(T value) {
    add(&value, sizeof value);
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

// The count, every keypoint field by field (no padding bytes), the descriptors, the F used and
// the blocks kept.
std::uint64_t features_hash(const Features& features);

}  // namespace aief::test

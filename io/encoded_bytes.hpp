#pragma once
// Bounds-checked random access to an encoded image's bytes, for the header parser
// (io/image_header.hpp) and the extent reader (io/image_extent.hpp): bytes already in memory, or
// a file read a page at a time through a ReadAt, so that the header and the extent of a file
// padded to gigabytes are read without holding the file (a 320 x 240 JPEG padded with zeros to
// 1.5 GB was read whole before decoding: 1.6 GB and 14 s).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

namespace aief::io {

// Reads up to `count` bytes at `offset` into `into`; returns how many it read (fewer only at the
// end of the file or on a read error).
using ReadAt =
    std::function<std::size_t(std::uint64_t offset, std::uint8_t* into, std::size_t count)>;

class EncodedBytes {
 public:
  EncodedBytes(const std::uint8_t* data, std::size_t size)
      : size_(size), page_data_(data), page_size_(size) {}
  EncodedBytes(ReadAt read, std::uint64_t size) : size_(size), read_(std::move(read)) {}

  std::uint64_t size() const { return size_; }

  // A read past the end (or a file that ends early) yields nullopt.
  std::optional<std::uint8_t> at(std::uint64_t index) const {
    if (index - page_start_ >= page_size_ && !load(index)) return std::nullopt;
    return page_data_[index - page_start_];
  }
  // The index of the first `byte` at or after `from`, nullopt when none is: memchr over each
  // page, not a call per byte (a JPEG's scan walked to its end through 1.5 GB of padding).
  std::optional<std::uint64_t> find(std::uint8_t byte, std::uint64_t from) const {
    while (from < size_) {
      if (from - page_start_ >= page_size_ && !load(from)) return std::nullopt;
      const std::uint8_t* start = page_data_ + (from - page_start_);
      const std::size_t left = static_cast<std::size_t>(page_size_ - (from - page_start_));
      if (const void* found = std::memchr(start, byte, left))
        return from + static_cast<std::uint64_t>(static_cast<const std::uint8_t*>(found) - start);
      from += left;
    }
    return std::nullopt;
  }
  bool starts_with(std::string_view magic, std::uint64_t at_index = 0) const {
    for (std::size_t i = 0; i < magic.size(); ++i)
      if (at(at_index + i) != static_cast<std::uint8_t>(magic[i])) return false;
    return true;
  }
  std::optional<std::uint64_t> big_endian(std::uint64_t at_index, int count) const {
    std::uint64_t value = 0;
    for (int i = 0; i < count; ++i) {
      const std::optional<std::uint8_t> byte = at(at_index + static_cast<std::uint64_t>(i));
      if (!byte) return std::nullopt;
      value = (value << 8) | *byte;
    }
    return value;
  }
  std::optional<std::uint64_t> little_endian(std::uint64_t at_index, int count) const {
    std::uint64_t value = 0;
    for (int i = count - 1; i >= 0; --i) {
      const std::optional<std::uint8_t> byte = at(at_index + static_cast<std::uint64_t>(i));
      if (!byte) return std::nullopt;
      value = (value << 8) | *byte;
    }
    return value;
  }

 private:
  static constexpr std::size_t kPageBytes = 1 << 16;

  // The page holding `index`, from the file; false past its end (in memory: always false).
  bool load(std::uint64_t index) const {
    if (!read_ || index >= size_) return false;
    page_.resize(kPageBytes);
    page_start_ = index - index % kPageBytes;
    const std::size_t wanted =
        static_cast<std::size_t>(std::min<std::uint64_t>(kPageBytes, size_ - page_start_));
    page_size_ = read_(page_start_, page_.data(), wanted);
    page_data_ = page_.data();
    return index - page_start_ < page_size_;
  }

  std::uint64_t size_;
  ReadAt read_;
  mutable std::vector<std::uint8_t> page_;
  mutable const std::uint8_t* page_data_ = nullptr;
  mutable std::uint64_t page_start_ = 0;
  mutable std::uint64_t page_size_ = 0;
};

}  // namespace aief::io

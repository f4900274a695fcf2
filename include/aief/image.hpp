#pragma once
// Gray 8-bit images: a non-owning view over caller memory (with a row stride, no copy) and a
// small owning buffer for the engine's own planes (pyramid levels, blurred levels).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace aief {

// Read-only view of a gray u8 plane. Row y starts at data + y * stride; stride >= width.
struct ImageView {
  const std::uint8_t* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;  // bytes between the starts of two rows

  const std::uint8_t* row(int y) const { return data + y * stride; }
  std::uint8_t at(int x, int y) const { return row(y)[x]; }
  bool empty() const { return width <= 0 || height <= 0 || data == nullptr; }
};

// Writable view of a gray u8 plane, same layout as ImageView.
struct MutableImageView {
  std::uint8_t* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;

  std::uint8_t* row(int y) const { return data + y * stride; }
  operator ImageView() const { return {data, width, height, stride}; }
};

// Owning gray u8 plane with stride == width. Reuses its storage when resized to a size it
// has held before, so a pipeline running on frames of one size allocates only once.
class GrayImage {
 public:
  GrayImage() = default;
  GrayImage(int width, int height) { resize(width, height); }

  void resize(int width, int height) {
    width_ = width;
    height_ = height;
    pixels_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  }
  int width() const { return width_; }
  int height() const { return height_; }
  std::uint8_t* data() { return pixels_.data(); }
  const std::uint8_t* data() const { return pixels_.data(); }
  ImageView view() const { return {pixels_.data(), width_, height_, width_}; }
  MutableImageView mutable_view() { return {pixels_.data(), width_, height_, width_}; }

 private:
  std::vector<std::uint8_t> pixels_;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace aief

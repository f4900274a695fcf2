// numpy image -> the engine's gray view (python/bindings.hpp).
#include <string>

#include "aief/error.hpp"
#include "io/image_io.hpp"
#include "python/bindings.hpp"

namespace aief::python {

namespace {

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i)
    text += (i ? ", " : "") + std::to_string(array.shape(i));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

}  // namespace

ImageInput::ImageInput(const py::object& image, long long max_pixels) {
  if (!py::isinstance<py::array>(image))
    throw Error("image must be a numpy array of uint8, got " +
                std::string(py::str(py::type::of(image).attr("__name__"))));
  // A masked array is an ndarray whose mask the engine would not see: refused while it masks any
  // pixel, rather than extracting from the pixels it hides.
  // numpy.ma.MaskedArray, looked up once and kept for the process's life: a plain array costs one
  // isinstance test.
  static PyObject* const masked_array =
      py::object(py::module_::import("numpy.ma").attr("MaskedArray")).release().ptr();
  if (PyObject_IsInstance(image.ptr(), masked_array) == 1 &&
      py::module_::import("numpy.ma").attr("is_masked")(image).cast<bool>())
    throw Error(
        "image is a numpy.ma.MaskedArray with masked pixels, "
        "which extract would read as they are: "
        "pass image.data to use them, or image.filled(value) to replace them");
  array_ = py::reinterpret_borrow<py::array>(image);
  const py::dtype dtype = array_.dtype();
  if (dtype.kind() != 'u' || dtype.itemsize() != 1)
    throw Error("image must be uint8, got dtype " + std::string(py::str(py::object(dtype))) +
                " (convert with .astype(numpy.uint8))");
  if (array_.ndim() != 2 && array_.ndim() != 3)
    throw Error("image must be 2-D (gray) or 3-D (H x W x 3 BGR or H x W x 4 BGRA), got shape " +
                shape_text(array_));
  channels_ = array_.ndim() == 3 ? static_cast<int>(array_.shape(2)) : 1;
  if (channels_ != 1 && channels_ != 3 && channels_ != 4)
    throw Error("image has " + std::to_string(channels_) + " channels, shape " +
                shape_text(array_) + " (expected 1, 3 BGR or 4 BGRA)");
  if (array_.shape(0) <= 0 || array_.shape(1) <= 0)
    throw Error("image is empty, shape " + shape_text(array_));
  // Checked on the shape, before any copy (a broadcast array of a few bytes may describe
  // gigabytes); compared by division: height x width may not fit in 64 bits.
  if (array_.shape(1) > max_pixels / array_.shape(0))
    throw Error("image of shape " + shape_text(array_) +
                " has more pixels than max_image_pixels = " + std::to_string(max_pixels) +
                " (refused before any copy)");
  height_ = static_cast<int>(array_.shape(0));
  width_ = static_cast<int>(array_.shape(1));
  row_stride_ = array_.strides(0);
  pixel_stride_ = array_.strides(1);
  channel_stride_ = array_.ndim() == 3 ? array_.strides(2) : 1;
  data_ = static_cast<const std::uint8_t*>(array_.data());
}

ImageView ImageInput::gray(GrayImage& buffer) const {
  const bool rows_contiguous = pixel_stride_ == channels_ &&
                               (channels_ == 1 || channel_stride_ == 1) &&
                               row_stride_ >= static_cast<py::ssize_t>(width_) * channels_;
  if (channels_ == 1) {
    if (rows_contiguous) return {data_, width_, height_, row_stride_};
    buffer.resize(width_, height_);
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        buffer.data()[static_cast<std::size_t>(y) * width_ + x] =
            data_[y * row_stride_ + x * pixel_stride_];
    return buffer.view();
  }
  if (rows_contiguous) {
    buffer = io::gray_from_pixels(data_, width_, height_, channels_, row_stride_, "numpy array");
    return buffer.view();
  }
  // Gather the interleaved pixels first, then the same conversion as for contiguous ones.
  std::vector<std::uint8_t> packed(static_cast<std::size_t>(width_) * height_ * channels_);
  std::size_t i = 0;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      for (int c = 0; c < channels_; ++c)
        packed[i++] = data_[y * row_stride_ + x * pixel_stride_ + c * channel_stride_];
  buffer = io::gray_from_pixels(packed.data(), width_, height_, channels_,
                                static_cast<std::ptrdiff_t>(width_) * channels_, "numpy array");
  return buffer.view();
}

}  // namespace aief::python

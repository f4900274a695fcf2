// aief.Extractor's work (python/py_extractor.hpp): extract, with an optional detection mask, and
// describe for given keypoints; the engine's Extractor::extract(image, mask) and ::describe.
#include <string>

#include "aief/error.hpp"
#include "core/frame/given_keypoints.hpp"
#include "python/bindings.hpp"
#include "python/extraction_rendezvous.hpp"
#include "python/py_extractor.hpp"

namespace aief::python {

namespace {

std::string dtype_text(const py::array& array) {
  return std::string(py::str(py::object(array.dtype())));
}

// A 2-D uint8 or bool numpy mask, C-contiguous (copied only when it is not).
py::array_t<std::uint8_t, py::array::c_style> mask_array(const py::object& mask) {
  if (!py::isinstance<py::array>(mask))
    throw Error("mask must be a 2-D numpy array of uint8 or bool, got " +
                std::string(py::str(py::type::of(mask).attr("__name__"))));
  auto array = py::reinterpret_borrow<py::array>(mask);
  const char kind = array.dtype().kind();
  if (!((kind == 'u' || kind == 'b') && array.dtype().itemsize() == 1))
    throw Error("mask must be uint8 or bool, got dtype " + dtype_text(array));
  if (array.ndim() != 2)
    throw Error("mask must be 2-D, got " + std::to_string(array.ndim()) + " dimensions");
  return py::array_t<std::uint8_t, py::array::c_style>::ensure(array.view("uint8"));
}

// A float32 column of n values from an optional array-like (None: `fallback` everywhere).
std::vector<float> column(const py::object& values, py::ssize_t n, float fallback,
                          const char* name) {
  std::vector<float> out(static_cast<std::size_t>(n), fallback);
  if (values.is_none()) return out;
  const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!array || array.ndim() != 1 || array.shape(0) != n)
    throw Error(std::string(name) + " must be " + std::to_string(n) + " numbers, one per keypoint");
  std::copy(array.data(), array.data() + n, out.begin());
  return out;
}

// The octave column: n levels of a pyramid of `n_levels`, each value checked as given (any
// dtype), before it narrows to int (2**40 wrapped to 0, 1.7 was cut to 1, NaN became INT_MIN).
std::vector<int> octave_column(const py::object& values, py::ssize_t n, int n_levels) {
  std::vector<int> out(static_cast<std::size_t>(n), 0);
  if (values.is_none()) return out;
  const auto given = py::array::ensure(values);
  const auto numbers =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!given || !numbers || numbers.ndim() != 1 || numbers.shape(0) != n)
    throw Error("octave must be " + std::to_string(n) + " integers, one per keypoint");
  for (py::ssize_t i = 0; i < n; ++i) {
    if (const std::string fault = octave_fault(numbers.at(i), n_levels); !fault.empty())
      throw Error("octave[" + std::to_string(i) + "] is " +
                  std::string(py::str(given[py::int_(i)])) + ", " + fault);
    out[static_cast<std::size_t>(i)] = static_cast<int>(numbers.at(i));
  }
  return out;
}

}  // namespace

PyFeatures PyExtractor::extract(const py::object& image, const py::object& mask) {
  const ImageInput input(image, extractor_.options().max_image_pixels);
  py::array_t<std::uint8_t, py::array::c_style> mask_pixels;
  ImageView mask_view;
  if (!mask.is_none()) {
    mask_pixels = mask_array(mask);
    mask_view = {mask_pixels.data(), static_cast<int>(mask_pixels.shape(1)),
                 static_cast<int>(mask_pixels.shape(0)),
                 static_cast<std::ptrdiff_t>(mask_pixels.shape(1))};
  }
  Features features;
  {
    py::gil_scoped_release no_gil;
    const std::lock_guard lock(mutex_);
    GrayImage buffer;
    const ImageView gray = input.gray(buffer);
    extraction_rendezvous();
    extractor_.extract(gray, mask_view, features);
    ++frames_;
  }
  return to_python(features);
}

py::tuple PyExtractor::describe(const py::object& image, const py::object& keypoints,
                                const py::object& octave, const py::object& size,
                                const py::object& angle, const py::object& response,
                                bool keep_angles) {
  const ImageInput input(image, extractor_.options().max_image_pixels);
  std::vector<Keypoint> given;
  if (py::isinstance<PyFeatures>(keypoints)) {
    const PyFeatures& f = features_of(keypoints);
    const auto xy = f.keypoints.unchecked<2>();
    for (py::ssize_t i = 0; i < xy.shape(0); ++i)
      given.push_back(
          {xy(i, 0), xy(i, 1), f.size.at(i), f.angle.at(i), f.response.at(i), f.octave.at(i)});
  } else {
    const auto xy =
        py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(keypoints);
    if (!xy || xy.ndim() != 2 || xy.shape(1) != 2)
      throw Error("keypoints must be aief Features or an N x 2 array of (x, y) level-0 pixels");
    const py::ssize_t n = xy.shape(0);
    const std::vector<float> sizes = column(size, n, static_cast<float>(kPatchSize), "size");
    if (keep_angles && angle.is_none())
      throw Error(
          "keep_angles=True keeps the given angles, but no angle= is given: pass angle= (degrees, "
          "one per keypoint), or leave keep_angles False to compute them");
    const std::vector<float> angles = column(angle, n, 0.0f, "angle");
    const std::vector<float> responses = column(response, n, 0.0f, "response");
    const std::vector<int> octaves = octave_column(octave, n, extractor_.options().n_levels);
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      given.push_back({xy.at(i, 0), xy.at(i, 1), sizes[k], angles[k], responses[k], octaves[k]});
    }
  }
  Features features;
  std::vector<std::int32_t> kept;
  {
    py::gil_scoped_release no_gil;
    const std::lock_guard lock(mutex_);
    GrayImage buffer;
    extractor_.describe(input.gray(buffer), given, features, &kept,
                        keep_angles ? GivenAngles::keep : GivenAngles::recompute);
  }
  py::array_t<std::int32_t> kept_array(static_cast<py::ssize_t>(kept.size()));
  std::copy(kept.begin(), kept.end(), kept_array.mutable_data());
  return py::make_tuple(to_python(features), kept_array);
}

}  // namespace aief::python

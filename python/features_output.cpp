// Engine features -> numpy arrays (python/bindings.hpp).
#include <algorithm>
#include <string>

#include "aief/error.hpp"
#include "python/bindings.hpp"

namespace aief::python {

const PyFeatures& features_of(const py::handle& object) {
  if (!py::isinstance<PyFeatures>(object))
    throw Error("expected aief.Features, got " +
                std::string(py::str(py::type::of(object).attr("__name__"))));
  return object.cast<const PyFeatures&>();  // refuses one made by __new__ alone
}

PyFeatures to_python(const Features& features) {
  const auto n = static_cast<py::ssize_t>(features.keypoints.size());
  PyFeatures out;
  out.keypoints = py::array_t<float>({n, py::ssize_t{2}});
  out.size = py::array_t<float>(n);
  out.angle = py::array_t<float>(n);
  out.response = py::array_t<float>(n);
  out.octave = py::array_t<std::int32_t>(n);
  out.descriptors = py::array_t<std::uint8_t>({n, py::ssize_t{kDescriptorBytes}});
  auto xy = out.keypoints.mutable_unchecked<2>();
  auto size = out.size.mutable_unchecked<1>();
  auto angle = out.angle.mutable_unchecked<1>();
  auto response = out.response.mutable_unchecked<1>();
  auto octave = out.octave.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Keypoint& kp = features.keypoints[static_cast<std::size_t>(i)];
    xy(i, 0) = kp.x;
    xy(i, 1) = kp.y;
    size(i) = kp.size;
    angle(i) = kp.angle_deg;
    response(i) = kp.response;
    octave(i) = kp.octave;
  }
  std::uint8_t* descriptors = out.descriptors.mutable_data();
  for (const Descriptor& d : features.descriptors)
    descriptors = std::copy(d.begin(), d.end(), descriptors);
  out.info = record_dict(features.info);
  out.image_width = features.image_width;
  out.image_height = features.image_height;
  out.descriptor = features.descriptor;
  return out;
}

std::vector<Descriptor> descriptors_from(const py::object& value, const char* name) {
  py::object source =
      py::isinstance<PyFeatures>(value) ? py::object(features_of(value).descriptors) : value;
  if (!py::isinstance<py::array>(source))
    throw Error(std::string(name) + " must be an N x 32 uint8 array or aief features, got " +
                std::string(py::str(py::type::of(value).attr("__name__"))));
  const auto array = py::reinterpret_borrow<py::array>(source);
  if (array.dtype().kind() != 'u' || array.dtype().itemsize() != 1 || array.ndim() != 2 ||
      array.shape(1) != kDescriptorBytes)
    throw Error(std::string(name) + " must be an N x 32 uint8 array, got dtype " +
                std::string(py::str(py::object(array.dtype()))) + " and " +
                std::to_string(array.ndim()) + " dimensions" +
                (array.ndim() == 2 ? " (" + std::to_string(array.shape(0)) + " x " +
                                         std::to_string(array.shape(1)) + ")"
                                   : ""));
  const auto rows = array.unchecked<std::uint8_t, 2>();
  std::vector<Descriptor> descriptors(static_cast<std::size_t>(array.shape(0)));
  for (py::ssize_t i = 0; i < array.shape(0); ++i)
    for (int b = 0; b < kDescriptorBytes; ++b)
      descriptors[static_cast<std::size_t>(i)][static_cast<std::size_t>(b)] = rows(i, b);
  return descriptors;
}

}  // namespace aief::python

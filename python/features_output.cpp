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

Features engine_features(const py::object& features) {
  const PyFeatures& f = features_of(features);
  const py::ssize_t n = f.keypoints.ndim() == 2 ? f.keypoints.shape(0) : -1;
  for (const py::array* field :
       {static_cast<const py::array*>(&f.size), static_cast<const py::array*>(&f.angle),
        static_cast<const py::array*>(&f.response), static_cast<const py::array*>(&f.octave)})
    if (n < 0 || f.keypoints.shape(1) != 2 || field->ndim() != 1 || field->shape(0) != n)
      throw Error("features: the keypoint arrays differ in length (not an aief.Features as made)");
  Features out;
  out.image_width = f.image_width;
  out.image_height = f.image_height;
  out.descriptor = f.descriptor;
  out.descriptors = descriptors_from(py::cast(f), "features");
  if (out.descriptors.size() != static_cast<std::size_t>(n))
    throw Error("features: " + std::to_string(out.descriptors.size()) + " descriptors for " +
                std::to_string(n) + " keypoints");
  const auto xy = f.keypoints.unchecked<2>();
  const auto size = f.size.unchecked<1>(), angle = f.angle.unchecked<1>(),
             response = f.response.unchecked<1>();
  const auto octave = f.octave.unchecked<1>();
  out.keypoints.resize(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    Keypoint& kp = out.keypoints[static_cast<std::size_t>(i)];
    kp.x = xy(i, 0);
    kp.y = xy(i, 1);
    kp.size = size(i);
    kp.angle_deg = angle(i);
    kp.response = response(i);
    kp.octave = octave(i);
  }
  return out;
}

}  // namespace aief::python

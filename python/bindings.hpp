#pragma once
// Shared by the files of the Python module (python/module.cpp opens it): numpy images in,
// numpy feature arrays out, and the functions that bind each part of the API.
#include <string>
#include <string_view>
#include <type_traits>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "aief/adapt.hpp"
#include "aief/features.hpp"
#include "aief/image.hpp"
#include "aief/options.hpp"
#include "io/record_fields.hpp"
#include "python/constructed_only.hpp"

namespace aief::python {

namespace py = pybind11;

// A caller's numpy image, described while the GIL is held, used after it is released. It keeps
// a reference to the array, so the pixels outlive the extraction.
class ImageInput {
 public:
  // uint8 arrays only: 2-D (gray, any strides), or 3-D H x W x C with C = 1, 3 (BGR) or 4
  // (BGRA), of at most `max_pixels` pixels (ExtractorOptions::max_image_pixels, checked on the
  // shape before anything is copied); not a numpy.ma.MaskedArray that masks pixels. Throws
  // aief::Error naming what is wrong.
  explicit ImageInput(const py::object& image,
                      long long max_pixels = ExtractorOptions{}.max_image_pixels);
  // The gray plane to extract from: the caller's own memory when its rows are contiguous (no
  // copy), else `buffer` filled by a strided copy; colour is converted into `buffer` exactly as
  // the CLI converts a decoded file (io/image_io.hpp). Needs no GIL.
  ImageView gray(GrayImage& buffer) const;

 private:
  py::array array_;
  const std::uint8_t* data_ = nullptr;
  int width_ = 0, height_ = 0, channels_ = 1;
  py::ssize_t row_stride_ = 0, pixel_stride_ = 0, channel_stride_ = 0;  // bytes
};

// The result object of Extractor.extract: numpy arrays that own copies of the features.
struct PyFeatures {
  py::array_t<float> keypoints;  // N x 2, x then y, level-0 pixels (OpenCV convention)
  py::array_t<float> size, angle, response;
  py::array_t<std::int32_t> octave;
  py::array_t<std::uint8_t> descriptors;  // N x 32
  py::dict info;
  int image_width = 0, image_height = 0;
  DescriptorKind descriptor = DescriptorKind::rbrief;  // what `descriptors` holds
};
PyFeatures to_python(const Features& features);
// The aief.Features `object` holds; aief.Error when it is none (or holds none: made by
// Features.__new__ alone, see python/constructed_only.hpp).
const PyFeatures& features_of(const py::handle& object);

// A result record (Features.info, AdaptResult.curve's rows) as a dict: its field list's keys and
// values, in order (io/record_fields.hpp).
template <class Record>
py::dict record_dict(const Record& record) {
  py::dict out;
  io::for_each_field(record, [&](std::string_view key, const auto& value) {
    out[py::str(key.data(), key.size())] = value;
  });
  return out;
}

// Its keys and Python types ("int", "float", "bool"), in order: what the stub's TypedDict says.
template <class Record>
py::list record_fields(const Record& record = {}) {
  py::list out;
  io::for_each_field(record, [&](std::string_view key, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    const char* type = std::is_same_v<T, bool> ? "bool" : std::is_integral_v<T> ? "int" : "float";
    out.append(py::make_tuple(py::str(key.data(), key.size()), type));
  });
  return out;
}
// N x 32 uint8 rows of a numpy array (or of a PyFeatures) as engine descriptors.
std::vector<Descriptor> descriptors_from(const py::object& value, const char* name);
// An aief.Features back as the engine's (everything but info); aief.Error when its arrays
// disagree in length.
Features engine_features(const py::object& features);

// A Python UserWarning saying `text`, where the CLI prints "aief: warning: <text>" (or a note):
// the same sentence, from the same source. Raises when the warnings filter makes it an error.
inline void warn(const std::string& text) {
  if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1) != 0) throw py::error_already_set();
}

// A file name given from Python (str, bytes or os.PathLike) as the bytes the system takes
// (os.fsencode: a str's undecodable bytes, kept as surrogates, come back as they were).
std::string filesystem_path(const py::handle& path);
// Bytes of a file name as Python gives file names (os.fsdecode): a str, never a decoding error.
py::object python_path(const std::string& bytes);

void bind_extractor(py::module_& m);
void bind_matching(py::module_& m);
void bind_batch(py::module_& m);
void bind_features_file(py::module_& m);
// After the classes are bound: pickle support for Extractor, Features and AdaptResult.
void bind_pickling(py::module_& m);
void bind_testing(py::module_& m);

}  // namespace aief::python

// Their objects made by __new__ alone are refused, not read (python/constructed_only.hpp).
namespace pybind11::detail {
template <>
class type_caster<aief::python::PyFeatures>
    : public aief::python::ConstructedOnlyCaster<aief::python::PyFeatures> {};
}  // namespace pybind11::detail

namespace pybind11::detail {
template <>
class type_caster<aief::AdaptResult>
    : public aief::python::ConstructedOnlyCaster<aief::AdaptResult> {};
}  // namespace pybind11::detail

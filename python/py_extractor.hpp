#pragma once
// The class behind aief.Extractor: one engine Extractor (buffers reused frame after frame). Its
// mutex serialises two Python threads sharing one; threads with an Extractor each run in parallel.
#include <mutex>
#include <string>
#include <vector>

#include "aief/extractor.hpp"
#include "core/options/option_table.hpp"
#include "python/bindings.hpp"

namespace aief::python {

class PyExtractor {
 public:
  // `given`: the keywords the options were resolved from (option_table::resolve_options), kept
  // for sweep_options().
  explicit PyExtractor(const ExtractorOptions& options,
                       std::vector<option_table::GivenOption> given = {})
      : extractor_(options), given_(std::move(given)) {}

  // Converts the image and extracts with the GIL released; mask (None: none) as
  // Extractor::extract's (python/py_extractor.cpp).
  PyFeatures extract(const py::object& image, const py::object& mask);
  // Extractor::describe: (features of the kept keypoints, their indices in the given ones).
  py::tuple describe(const py::object& image, const py::object& keypoints, const py::object& octave,
                     const py::object& size, const py::object& angle, const py::object& response,
                     bool keep_angles);

  const ExtractorOptions& options() const { return extractor_.options(); }
  const std::vector<option_table::GivenOption>& given() const { return given_; }
  // The options for the adaptive sweep (aief.adapt): the given keywords resolved again for it, so
  // one the sweep never reads is refused with aief adapt's message (option_table::Use::sweep).
  const ExtractorOptions& sweep_options() const {
    option_table::resolve_options(given_, option_table::Use::sweep);
    return options();
  }
  // Frames extracted so far: a carried extractor's F and sweep depend on them.
  long long frames() const { return frames_; }
  std::string kernel_name() const { return std::string(extractor_.kernel_name()); }

 private:
  Extractor extractor_;
  std::vector<option_table::GivenOption> given_;
  std::mutex mutex_;
  long long frames_ = 0;  // under mutex_
};

}  // namespace aief::python

namespace pybind11::detail {
template <>
class type_caster<aief::python::PyExtractor>
    : public aief::python::ConstructedOnlyCaster<aief::python::PyExtractor> {};
}  // namespace pybind11::detail

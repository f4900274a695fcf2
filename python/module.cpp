// The Python module aief._aief (python/aief/__init__.py re-exports it): the engine's extractor,
// matcher, RANSAC and adaptive sweep on numpy arrays. aief.Error is a ValueError carrying the
// engine's message.
#include "aief/error.hpp"
#include "aief/version.hpp"
#include "python/bindings.hpp"

PYBIND11_MODULE(_aief, m) {
  namespace py = pybind11;
  m.doc() =
      "AIEF ORB features (adaptive information entropy): "
      "extraction, matching, RANSAC, adaptive threshold";
  py::register_exception<aief::Error>(m, "Error", PyExc_ValueError).attr("__doc__") =
      "Bad input or options (a ValueError): the engine's message says what and where";
  aief::python::bind_extractor(m);
  aief::python::bind_matching(m);
  aief::python::bind_batch(m);
  aief::python::bind_features_file(m);
  aief::python::bind_pickling(m);
  aief::python::bind_testing(m);
  m.attr("__version__") = aief::kVersionString;
}

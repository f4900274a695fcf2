// File names between Python and the engine (python/bindings.hpp): Linux file names are bytes,
// Python's are str with the bytes that are not UTF-8 kept as surrogates (os.fsencode and
// os.fsdecode, PEP 383), so every name the CLI reads round-trips.
#include "python/bindings.hpp"

namespace aief::python {

std::string filesystem_path(const py::handle& path) {
  // os.fsencode takes str, bytes and any os.PathLike (pathlib.Path), and raises TypeError for
  // anything else, naming its type.
  return py::module_::import("os").attr("fsencode")(path).cast<std::string>();
}

py::object python_path(const std::string& bytes) {
  return py::module_::import("os").attr("fsdecode")(py::bytes(bytes));
}

}  // namespace aief::python

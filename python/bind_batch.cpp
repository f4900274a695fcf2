// aief.batch_inputs: which images a batch takes and their names, the CLI's own rule
// (io/batch_inputs.hpp), so the Dask recipe (aief/dask_batch.py) makes the CLI's groups.
#include <pybind11/stl.h>

#include "io/batch_inputs.hpp"
#include "python/bindings.hpp"

namespace aief::python {

void bind_batch(py::module_& m) {
  m.def(
      "batch_inputs",
      [](const py::object& folder_or_list_given) {
        const std::string folder_or_list = filesystem_path(folder_or_list_given);
        std::vector<io::BatchInput> inputs;
        {
          py::gil_scoped_release no_gil;
          inputs = io::list_batch_inputs(folder_or_list);
        }
        py::list out;
        for (const io::BatchInput& input : inputs)  // names that are not UTF-8 as os.fsdecode
          out.append(py::make_tuple(python_path(input.path), python_path(input.name)));
        return out;
      },
      py::arg("folder_or_list"),
      "The images `aief extract --batch FOLDER_OR_LIST` takes, "
      "as (path, name) pairs sorted by name: "
      "a folder's image files recursively (folder symlinks followed, cycles not; "
      "broken links and other non-files listed so that reading them reports them), "
      "or a list file's lines. The name is the group / output key.");
}

}  // namespace aief::python

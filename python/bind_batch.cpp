// aief.batch_inputs: which images a batch takes and their names, the CLI's own rule
// (io/batch_inputs.hpp), so the Dask recipe (aief/dask_batch.py) makes the CLI's groups.
#include <pybind11/stl.h>

#include "io/batch_inputs.hpp"
#include "python/bindings.hpp"

namespace aief::python {

void bind_batch(py::module_& m) {
  m.def(
      "batch_inputs",
      [](const std::string& folder_or_list) {
        std::vector<io::BatchInput> inputs;
        {
          py::gil_scoped_release no_gil;
          inputs = io::list_batch_inputs(folder_or_list);
        }
        std::vector<std::pair<std::string, std::string>> out;
        out.reserve(inputs.size());
        for (io::BatchInput& input : inputs)
          out.emplace_back(std::move(input.path), std::move(input.name));
        return out;
      },
      py::arg("folder_or_list"),
      "The images `aief extract --batch FOLDER_OR_LIST` takes, as (path, name) pairs sorted by "
      "name: a folder's "
      "image files recursively (folder symlinks followed, cycles not; broken links and other "
      "non-files listed so "
      "that reading them reports them), or a list file's lines. The name is the group / output "
      "key.");
}

}  // namespace aief::python

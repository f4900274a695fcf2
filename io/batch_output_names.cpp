#include "io/batch_output_names.hpp"

#include <filesystem>
#include <set>

#include "aief/error.hpp"

namespace aief::io {

namespace fs = std::filesystem;

std::string batch_output_path(const std::string& output_dir, const std::string& name,
                              const std::string& format) {
  std::string relative;
  std::size_t begin = 0;
  if (!name.empty() && name[0] == '/') {
    relative = "%2F";
    begin = 1;
  }
  while (begin < name.size()) {
    std::size_t end = name.find('/', begin);
    if (end == std::string::npos) end = name.size();
    std::string part = name.substr(begin, end - begin);
    if (part == "..") {
      part = "%2E%2E";
    } else {
      for (std::size_t at = 0; (at = part.find('%', at)) != std::string::npos; at += 3)
        part.replace(at, 1, "%25");
    }
    if (!part.empty()) relative += (relative.empty() ? "" : "/") + part;
    begin = end + 1;
  }
  return (fs::path(output_dir) / (relative + "." + format)).string();
}

void check_batch_outputs_do_not_nest(const std::vector<BatchInput>& inputs,
                                     const std::string& output_dir, const std::string& format) {
  std::set<std::string> files;
  for (const BatchInput& input : inputs) files.insert(batch_output_path("", input.name, format));
  for (const BatchInput& input : inputs)
    for (fs::path folder = fs::path(batch_output_path("", input.name, format)).parent_path();
         !folder.empty(); folder = folder.parent_path())
      if (files.count(folder.string()))
        throw Error("batch input '" + input.path + "' needs the folder '" + folder.string() +
                    "' in '" + output_dir + "', which is another input's output file");
}

}  // namespace aief::io

#include "io/batch_output_names.hpp"

#include <filesystem>
#include <set>

#include "aief/error.hpp"
#include "io/feature_formats.hpp"

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
  if (const FeatureFormat* one_file = feature_format_named(format);
      one_file && one_file->layout == FeatureFormat::Layout::one_file_per_batch) {
    // A group per name: a name may not be the folder of another ("a" and "a/x.png").
    std::set<std::string> names;
    for (const BatchInput& input : inputs) names.insert(input.name);
    for (const BatchInput& input : inputs)
      for (std::size_t at = input.name.find('/', 1); at != std::string::npos;
           at = input.name.find('/', at + 1))
        if (names.count(input.name.substr(0, at)))
          throw Error("batch input '" + input.path +
                      "' would have its group inside the group of input '" +
                      input.name.substr(0, at) + "' in '" + output_dir +
                      "' (one name is the folder of the other's); nothing was written");
    return;
  }
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

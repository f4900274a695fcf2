#include "io/batch_inputs.hpp"

#include <algorithm>
#include <filesystem>

#include "aief/error.hpp"
#include "io/image_formats.hpp"
#include "io/text_list.hpp"

namespace aief::io {

namespace fs = std::filesystem;

namespace {

// The images below `folder`, named by their path below the batch root (`prefix`).
void list_folder(const fs::path& folder, const std::string& prefix,
                 std::vector<fs::path>& open_folders, std::vector<BatchInput>& out) {
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = prefix + entry.path().filename().string();
    std::error_code ec;
    if (entry.is_directory(ec)) {
      const fs::path real = fs::canonical(entry.path(), ec);
      if (ec || std::find(open_folders.begin(), open_folders.end(), real) != open_folders.end())
        continue;
      open_folders.push_back(real);
      list_folder(entry.path(), name + "/", open_folders, out);
      open_folders.pop_back();
    } else if (has_readable_image_extension(entry.path().string())) {
      out.push_back({entry.path().string(), name});
    }
  }
}

std::vector<BatchInput> list_file_inputs(const std::string& list) {
  std::vector<BatchInput> inputs;
  for (std::string& line : read_text_list(list, "batch list")) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (!line.empty() && line[0] != '#') inputs.push_back({line, name_of_listed_path(line)});
  }
  return inputs;
}

}  // namespace

std::string name_of_listed_path(const std::string& line) {
  std::string name = !line.empty() && line[0] == '/' ? "/" : "";
  std::size_t begin = 0;
  while (begin <= line.size()) {
    std::size_t end = line.find('/', begin);
    if (end == std::string::npos) end = line.size();
    const std::string part = line.substr(begin, end - begin);
    if (!part.empty() && part != ".") name += (name.empty() || name == "/" ? "" : "/") + part;
    begin = end + 1;
  }
  return name;
}

std::vector<BatchInput> list_batch_inputs(const std::string& folder_or_list) {
  std::vector<BatchInput> all;
  std::error_code ec;
  if (fs::is_directory(folder_or_list, ec)) {
    std::vector<fs::path> open_folders = {fs::canonical(folder_or_list, ec)};
    try {
      list_folder(folder_or_list, "", open_folders, all);
    } catch (const fs::filesystem_error& e) {
      throw Error("cannot list '" + folder_or_list + "': " + e.code().message());
    }
  } else {
    all = list_file_inputs(folder_or_list);
  }
  std::sort(all.begin(), all.end(),
            [](const BatchInput& a, const BatchInput& b) { return a.name < b.name; });
  all.erase(std::unique(all.begin(), all.end(),
                        [](const BatchInput& a, const BatchInput& b) { return a.name == b.name; }),
            all.end());
  return all;
}

std::vector<BatchInput> shard_of(const std::vector<BatchInput>& inputs, int index, int count) {
  std::vector<BatchInput> mine;
  for (std::size_t i = static_cast<std::size_t>(index); i < inputs.size();
       i += static_cast<std::size_t>(count))
    mine.push_back(inputs[i]);
  return mine;
}

}  // namespace aief::io

#include "io/batch_inputs.hpp"

#include <algorithm>
#include <filesystem>
#include <unordered_set>

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

bool natural_less(const std::string& a, const std::string& b) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  std::size_t i = 0, j = 0;
  int zeros = 0;  // leading zeros of a's numbers minus b's, the first that differ: the tie-break
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      std::size_t zi = i, zj = j;
      while (zi < a.size() && a[zi] == '0') ++zi;
      while (zj < b.size() && b[zj] == '0') ++zj;
      std::size_t ei = zi, ej = zj;
      while (ei < a.size() && digit(a[ei])) ++ei;
      while (ej < b.size() && digit(b[ej])) ++ej;
      if (ei - zi != ej - zj) return ei - zi < ej - zj;  // more significant digits: larger
      const int order = a.compare(zi, ei - zi, b, zj, ej - zj);
      if (order != 0) return order < 0;
      if (zeros == 0) zeros = static_cast<int>(zi - i) - static_cast<int>(zj - j);
      i = ei;
      j = ej;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return zeros != 0 ? zeros < 0 : false;
}

std::string frame_order_of(const std::string& folder_or_list) {
  std::error_code ec;
  return fs::is_directory(folder_or_list, ec)
             ? "in natural order of their names (numbers as numbers: frame_2 before frame_10)"
             : "in the list's order";
}

std::vector<BatchInput> list_batch_inputs(const std::string& folder_or_list, InputOrder order) {
  std::vector<BatchInput> all;
  std::error_code ec;
  if (order == InputOrder::frames) {
    const bool folder = fs::is_directory(folder_or_list, ec);
    if (!folder) {  // a list: as listed, a name listed twice taken where it is first
      std::unordered_set<std::string> seen;
      for (BatchInput& input : list_file_inputs(folder_or_list))
        if (seen.insert(input.name).second) all.push_back(std::move(input));
      return all;
    }
    all = list_batch_inputs(folder_or_list, InputOrder::by_name);
    std::stable_sort(all.begin(), all.end(), [](const BatchInput& a, const BatchInput& b) {
      return natural_less(a.name, b.name);
    });
    return all;
  }
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

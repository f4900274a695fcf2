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

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// The end of the decimal fraction after a run of digits ending at `at` ("." and digits), or `at`
// when none follows.
std::size_t fraction_end(const std::string& text, std::size_t at) {
  if (at + 1 >= text.size() || text[at] != '.' || !is_digit(text[at + 1])) return at;
  std::size_t end = at + 1;
  while (end < text.size() && is_digit(text[end])) ++end;
  return end;
}

// Fractions' digits (after the '.') by value: the shorter padded with zeros (.05 < .1 = .10).
int compare_fractions(const std::string& a, std::size_t a_begin, std::size_t a_end,
                      const std::string& b, std::size_t b_begin, std::size_t b_end) {
  const std::size_t length = std::max(a_end - a_begin, b_end - b_begin);
  for (std::size_t k = 0; k < length; ++k) {
    const char x = a_begin + k < a_end ? a[a_begin + k] : '0';
    const char y = b_begin + k < b_end ? b[b_begin + k] : '0';
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

}  // namespace

bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  // The first difference in how a number of equal value is written (leading zeros, then the
  // fraction's digits: a's minus b's), the tie-break: "2" before "02", "0.1" before "0.10".
  int spelling = 0;
  while (i < a.size() && j < b.size()) {
    if (is_digit(a[i]) && is_digit(b[j])) {
      std::size_t zi = i, zj = j;
      while (zi < a.size() && a[zi] == '0') ++zi;
      while (zj < b.size() && b[zj] == '0') ++zj;
      std::size_t ei = zi, ej = zj;
      while (ei < a.size() && is_digit(a[ei])) ++ei;
      while (ej < b.size() && is_digit(b[ej])) ++ej;
      if (ei - zi != ej - zj) return ei - zi < ej - zj;  // more significant digits: larger
      const int order = a.compare(zi, ei - zi, b, zj, ej - zj);
      if (order != 0) return order < 0;
      if (spelling == 0) spelling = static_cast<int>(zi - i) - static_cast<int>(zj - j);
      // A decimal fraction right after the number (seconds: 0.033333 before 0.1) by its value;
      // a number without one counts as .0.
      const std::size_t fi = fraction_end(a, ei), fj = fraction_end(b, ej);
      if (fi != ei || fj != ej) {
        const std::size_t ai = fi != ei ? ei + 1 : ei, bj = fj != ej ? ej + 1 : ej;
        const int fraction = compare_fractions(a, ai, fi, b, bj, fj);
        if (fraction != 0) return fraction < 0;
        if (spelling == 0) spelling = static_cast<int>(fi - ei) - static_cast<int>(fj - ej);
      }
      i = fi;
      j = fj;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return spelling != 0 ? spelling < 0 : false;
}

std::string frame_order_of(const std::string& folder_or_list) {
  std::error_code ec;
  return fs::is_directory(folder_or_list, ec)
             ? "in natural order of their names (numbers by value, decimal fractions too: "
               "frame_2 before frame_10, 0.05 before 0.1)"
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

#include "io/pairs_file.hpp"

#include <sstream>

#include "aief/error.hpp"
#include "io/text_list.hpp"

namespace aief::io {

std::vector<ImagePair> read_pairs(const std::string& path) {
  std::vector<ImagePair> pairs;
  int number = 0;
  for (const std::string& line : read_text_list(path, "pairs file", 2)) {  // a folder, a binary file: refused
    ++number;
    std::istringstream fields(line);
    std::string first, second, extra;
    if (!(fields >> first) || first[0] == '#') continue;
    if (!(fields >> second) || (fields >> extra))
      throw Error("pairs file '" + path + "' line " + std::to_string(number) + ": expected two image names, got '" + line + "'");
    pairs.emplace_back(first, second);
  }
  return pairs;
}

}  // namespace aief::io

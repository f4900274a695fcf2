#include "io/pairs_file.hpp"

#include <fstream>
#include <sstream>

#include "aief/error.hpp"

namespace aief::io {

std::vector<ImagePair> read_pairs(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read pairs file '" + path + "'");
  std::vector<ImagePair> pairs;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
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

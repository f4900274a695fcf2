#include "io/pairs_file.hpp"

#include <algorithm>
#include <sstream>
#include <unordered_map>

#include "aief/error.hpp"
#include "io/text_list.hpp"

namespace aief::io {

std::string hloc_pair_name(const std::string& name0, const std::string& name1) {
  std::string a = name0, b = name1;
  std::replace(a.begin(), a.end(), '/', '-');
  std::replace(b.begin(), b.end(), '/', '-');
  return a + "/" + b;
}

PairsList read_pairs(const std::string& path) {
  PairsList list;
  struct Seen {
    ImagePair pair;
    int line;
  };
  std::unordered_map<std::string, Seen> groups;  // hloc group -> the first pair and line naming it
  int number = 0;
  for (const std::string& line :
       read_text_list(path, "pairs file", 2)) {  // a folder, a binary file: refused
    ++number;
    const std::string where = "pairs file '" + path + "' line " + std::to_string(number);
    std::istringstream fields(line);
    std::string first, second, extra;
    if (!(fields >> first)) continue;
    if (first[0] == '#') {
      list.notes.push_back(where + " skipped: it begins with '#', read as a comment ('" + line +
                           "')");
      continue;
    }
    if (!(fields >> second) || (fields >> extra))
      throw Error(where + ": expected two image names, got '" + line + "'");
    if (first == second) {
      list.notes.push_back(where + " skipped: '" + first + "' paired with itself");
      continue;
    }
    const auto [at, inserted] =
        groups.emplace(hloc_pair_name(first, second), Seen{{first, second}, number});
    if (!inserted) {
      if (at->second.pair == ImagePair(first, second)) continue;  // listed again
      throw Error(
          where + " ('" + first + " " + second + "') and line " + std::to_string(at->second.line) +
          " ('" + at->second.pair.first + " " + at->second.pair.second +
          "') name one pair group '" + at->first +
          "' in hloc's matches layout ('/' in a name becomes '-'): rename one of the images");
    }
    list.pairs.emplace_back(first, second);
  }
  return list;
}

}  // namespace aief::io

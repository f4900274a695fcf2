#include "io/pairs_file.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "aief/error.hpp"
#include "io/text_list.hpp"

namespace aief::io {

namespace {

std::string hloc_image_name(std::string name) {
  std::replace(name.begin(), name.end(), '/', '-');
  return name;
}

// Each distinct name once, with the index of its hloc form ('/' as '-'): two pairs share a group
// exactly when their names' hloc forms are the same, in the same order (a hloc form holds no '/',
// so the group name splits back into the two).
class NameIndex {
 public:
  explicit NameIndex(std::vector<std::string>& names) : names_(names) {}
  std::uint32_t id(const std::string& name) {
    const auto [at, inserted] = ids_.emplace(name, static_cast<std::uint32_t>(names_.size()));
    if (inserted) {
      if (names_.size() == std::numeric_limits<std::uint32_t>::max())
        throw Error("pairs file names more than 4294967295 images");
      names_.push_back(name);
      const auto hloc =
          hloc_ids_.emplace(hloc_image_name(name), static_cast<std::uint32_t>(hloc_ids_.size()));
      hloc_id_.push_back(hloc.first->second);
    }
    return at->second;
  }
  // The same key for exactly the pairs that share a group in a matches file.
  std::uint64_t group_key(std::uint32_t id0, std::uint32_t id1) const {
    return std::uint64_t{hloc_id_[id0]} << 32 | hloc_id_[id1];
  }

 private:
  std::vector<std::string>& names_;
  std::unordered_map<std::string, std::uint32_t> ids_;
  std::unordered_map<std::string, std::uint32_t> hloc_ids_;
  std::vector<std::uint32_t> hloc_id_;  // by name id
};

}  // namespace

std::string hloc_pair_name(const std::string& name0, const std::string& name1) {
  return hloc_image_name(name0) + "/" + hloc_image_name(name1);
}

PairsList read_pairs(const std::string& path) {
  PairsList list;
  NameIndex index(list.names);
  struct FirstPair {
    std::uint32_t pair;  // its index in list.pairs
    std::uint32_t line;
  };
  std::unordered_map<std::uint64_t, FirstPair> groups;  // group key -> the first pair naming it
  std::uint32_t number = 0;
  for_each_text_line(path, "pairs file", 2, [&](const std::string& line) {  // a folder, a binary
                                                                            // file: refused
    ++number;
    const std::string where = "pairs file '" + path + "' line " + std::to_string(number);
    std::istringstream fields(line);
    std::string first, second, extra;
    if (!(fields >> first)) return;
    if (first[0] == '#') {
      list.notes.push_back(where + " skipped: it begins with '#', read as a comment ('" + line +
                           "')");
      return;
    }
    if (!(fields >> second) || (fields >> extra))
      throw Error(where + ": expected two image names, got '" + line + "'");
    if (first == second) {
      list.notes.push_back(where + " skipped: '" + first + "' paired with itself");
      return;
    }
    const std::uint32_t id0 = index.id(first);  // in this order: names are numbered as met
    const std::pair<std::uint32_t, std::uint32_t> ids(id0, index.id(second));
    const auto [at, inserted] =
        groups.emplace(index.group_key(ids.first, ids.second),
                       FirstPair{static_cast<std::uint32_t>(list.pairs.size()), number});
    if (!inserted) {
      const std::uint32_t earlier = at->second.pair;
      if (list.pairs[earlier] == ids) return;  // listed again
      throw Error(where + " ('" + first + " " + second + "') and line " +
                  std::to_string(at->second.line) + " ('" + list.name0(earlier) + " " +
                  list.name1(earlier) + "') name one pair group '" + hloc_pair_name(first, second) +
                  "' in hloc's matches layout ('/' in a name becomes '-'): rename one of the "
                  "images");
    }
    list.pairs.push_back(ids);
  });
  // A file of no line at all is refused, not done in silence (`colmap --pairs /dev/null` wrote a
  // database of no pairs and exited 0); lines all skipped are said by their notes.
  if (list.pairs.empty() && list.notes.empty())
    throw Error("pairs file '" + path + "' names no pair (" +
                (number == 0 ? std::string("it is empty")
                             : std::to_string(number) + " line(s), all blank") +
                "): hloc's pairs files hold one 'name0 name1' line per pair");
  return list;
}

}  // namespace aief::io

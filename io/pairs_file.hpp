#pragma once
// hloc's pairs.txt: one image pair per line, "name0 name1" (names as in the features file, no
// spaces). hloc's files have no comments: a line whose first name begins with '#' is skipped as
// one, but said (a note naming the line), since an image may be named so.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace aief::io {

using ImagePair = std::pair<std::string, std::string>;

// A pairs file held compactly, as a collection's list of a million pairs needs: each image name
// once, each pair as two indices into the names (about 50 bytes a pair with the check for pairs
// sharing a group, against about 500 for two strings a pair).
struct PairsList {
  std::vector<std::string> names;  // every image named, once, in the order first named
  // Each pair as the indices of its two names, in file order; self-pairs and repeated lines
  // left out.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<std::string> notes;  // what was left out and why: "pairs file 'p' line 3: ..."

  std::size_t size() const { return pairs.size(); }
  const std::string& name0(std::size_t pair) const { return names[pairs[pair].first]; }
  const std::string& name1(std::size_t pair) const { return names[pairs[pair].second]; }
  ImagePair pair(std::size_t pair) const { return {name0(pair), name1(pair)}; }
};

// Throws aief::Error naming the file and the line that is not two names, the two lines whose
// pairs would share one group in a matches file (hloc_pair_name: "a/b.png c.png" and
// "a-b.png c.png"), or a file of no line but blank ones (/dev/null), before any work. The file is
// read as a stream (io/text_list.hpp).
PairsList read_pairs(const std::string& path);

// hloc's names_to_pair(name0, name1), the matches file's group of a pair: each name with '/'
// replaced by '-', joined by '/' ("a/b.png", "c.png" -> "a-b.png/c.png"). Two pairs can share
// one (hloc's own convention); a matches file records both names to tell them apart.
std::string hloc_pair_name(const std::string& name0, const std::string& name1);

}  // namespace aief::io

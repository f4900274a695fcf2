#pragma once
// hloc's pairs.txt: one image pair per line, "name0 name1" (names as in the features file, no
// spaces). hloc's files have no comments: a line whose first name begins with '#' is skipped as
// one, but said (a note naming the line), since an image may be named so.
#include <string>
#include <utility>
#include <vector>

namespace aief::io {

using ImagePair = std::pair<std::string, std::string>;

struct PairsList {
  std::vector<ImagePair> pairs;    // in file order; self-pairs and repeated lines left out
  std::vector<std::string> notes;  // what was left out and why: "pairs file 'p' line 3: ..."
};

// Throws aief::Error naming the file and the line that is not two names, or the two lines whose
// pairs would share one group in a matches file (hloc_pair_name: "a/b.png c.png" and
// "a-b.png c.png"), before any work.
PairsList read_pairs(const std::string& path);

// hloc's names_to_pair(name0, name1), the matches file's group of a pair: each name with '/'
// replaced by '-', joined by '/' ("a/b.png", "c.png" -> "a-b.png/c.png"). Two pairs can share
// one (hloc's own convention); a matches file records both names to tell them apart.
std::string hloc_pair_name(const std::string& name0, const std::string& name1);

}  // namespace aief::io

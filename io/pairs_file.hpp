#pragma once
// hloc's pairs.txt: one image pair per line, "name0 name1" (names as in the features file,
// no spaces); blank lines and lines starting with '#' are skipped.
#include <string>
#include <utility>
#include <vector>

namespace aief::io {

using ImagePair = std::pair<std::string, std::string>;

// Throws aief::Error naming the file and the line that is not two names.
std::vector<ImagePair> read_pairs(const std::string& path);

}  // namespace aief::io

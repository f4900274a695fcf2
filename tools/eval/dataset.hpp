#pragma once
// The Oxford affine sequences on disk: <dataset>/<seq>/img1..6.(png|ppm|pgm), H1to2p..H1to6p.
#include <string>
#include <vector>

#include "aief/homography.hpp"

namespace aief::eval {

inline const std::vector<std::string> kAllSequences = {"bark",   "bikes", "boat", "graf",
                                                       "leuven", "trees", "ubc",  "wall"};
// The pairs of the paper's tables (img1 -> img2).
inline const std::vector<std::string> kPaperSequences = {"graf", "leuven", "boat", "bikes"};

struct PairInput {
  std::string sequence;
  int target = 2;  // img1 -> img<target>
  std::string path_a, path_b;
  std::string truth_path;  // the homography file, H1to<target>p
  Homography truth{};
};

// Reads a 3x3 homography written as 9 numbers (any float syntax). Throws aief::Error for fewer or
// more numbers, a NaN or infinity, and a singular or all-zero matrix (no ground truth).
Homography read_homography_file(const std::string& path);

// The pairs img1 -> img2 (all_pairs false) or img1 -> img2..6 of each sequence. Throws
// aief::Error naming the first missing file.
std::vector<PairInput> find_pairs(const std::string& dataset,
                                  const std::vector<std::string>& sequences, bool all_pairs);

}  // namespace aief::eval

#include "tools/eval/dataset.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "aief/error.hpp"

namespace aief::eval {

namespace {
// |det H| / (product of H's column lengths) below this: singular. The bundled Oxford ground
// truths lie above 1e-3; a rank-deficient matrix gives rounding noise, about 1e-16.
constexpr double kSingularRatio = 1e-10;
}  // namespace

Homography read_homography_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot open homography '" + path + "'");
  Homography H{};
  for (double& value : H) {
    std::string token;
    if (!(in >> token)) throw Error("homography '" + path + "' holds fewer than 9 numbers");
    try {
      std::size_t used = 0;
      value = std::stod(token, &used);
      if (used != token.size()) throw Error(token);
    } catch (const std::exception&) {
      throw Error("homography '" + path + "': '" + token + "' is not a number");
    }
    if (!std::isfinite(value))
      throw Error("homography '" + path + "': '" + token + "' is not a finite number");
  }
  if (std::string extra; in >> extra)
    throw Error("homography '" + path + "' holds more than 9 numbers ('" + extra + "' follows)");
  // Singular (all zero included): no inverse, so no ground truth. Judged by the determinant over
  // the product of the column lengths (Hadamard's bound), 0 for a singular matrix and 1 for an
  // orthogonal one, whatever the scale and the translation.
  if (std::all_of(H.begin(), H.end(), [](double v) { return v == 0; }))
    throw Error("homography '" + path + "' is all zeros");
  double bound = 1;
  for (int c = 0; c < 3; ++c)
    bound *= std::hypot(H[static_cast<std::size_t>(c)], H[static_cast<std::size_t>(3 + c)],
                        H[static_cast<std::size_t>(6 + c)]);
  if (bound == 0) throw Error("homography '" + path + "' is singular (a column of zeros)");
  const auto at = [&](int r, int c) { return H[static_cast<std::size_t>(3 * r + c)]; };
  const double det = at(0, 0) * (at(1, 1) * at(2, 2) - at(1, 2) * at(2, 1)) -
                     at(0, 1) * (at(1, 0) * at(2, 2) - at(1, 2) * at(2, 0)) +
                     at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
  if (std::abs(det) < kSingularRatio * bound)
    throw Error("homography '" + path + "' is singular (no inverse, so no ground truth)");
  return H;
}

namespace {

std::string image_path(const std::filesystem::path& folder, int index) {
  for (const char* ext : {".png", ".ppm", ".pgm", ".jpg"}) {
    const std::filesystem::path candidate = folder / ("img" + std::to_string(index) + ext);
    if (std::filesystem::exists(candidate)) return candidate.string();
  }
  throw Error("missing image " + (folder / ("img" + std::to_string(index) + ".png")).string());
}

}  // namespace

std::vector<PairInput> find_pairs(const std::string& dataset,
                                  const std::vector<std::string>& sequences, bool all_pairs) {
  if (!std::filesystem::is_directory(dataset))
    throw Error("dataset folder '" + dataset + "' does not exist");
  std::vector<PairInput> pairs;
  for (const std::string& sequence : sequences) {
    const std::filesystem::path folder = std::filesystem::path(dataset) / sequence;
    if (!std::filesystem::is_directory(folder))
      throw Error("sequence folder '" + folder.string() + "' does not exist");
    const int last = all_pairs ? 6 : 2;
    for (int target = 2; target <= last; ++target) {
      PairInput pair;
      pair.sequence = sequence;
      pair.target = target;
      pair.path_a = image_path(folder, 1);
      pair.path_b = image_path(folder, target);
      pair.truth_path = (folder / ("H1to" + std::to_string(target) + "p")).string();
      pair.truth = read_homography_file(pair.truth_path);
      pairs.push_back(std::move(pair));
    }
  }
  return pairs;
}

}  // namespace aief::eval

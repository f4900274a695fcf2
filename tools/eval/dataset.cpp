#include "tools/eval/dataset.hpp"

#include <filesystem>
#include <fstream>

#include "aief/error.hpp"

namespace aief::eval {

Homography read_homography_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot open homography '" + path + "'");
  Homography H{};
  for (double& value : H) {
    std::string token;
    if (!(in >> token)) throw Error("homography '" + path + "' holds fewer than 9 numbers");
    try {
      value = std::stod(token);
    } catch (const std::exception&) {
      throw Error("homography '" + path + "': '" + token + "' is not a number");
    }
  }
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

std::vector<PairInput> find_pairs(const std::string& dataset, const std::vector<std::string>& sequences, bool all_pairs) {
  if (!std::filesystem::is_directory(dataset)) throw Error("dataset folder '" + dataset + "' does not exist");
  std::vector<PairInput> pairs;
  for (const std::string& sequence : sequences) {
    const std::filesystem::path folder = std::filesystem::path(dataset) / sequence;
    if (!std::filesystem::is_directory(folder)) throw Error("sequence folder '" + folder.string() + "' does not exist");
    const int last = all_pairs ? 6 : 2;
    for (int target = 2; target <= last; ++target) {
      PairInput pair;
      pair.sequence = sequence;
      pair.target = target;
      pair.path_a = image_path(folder, 1);
      pair.path_b = image_path(folder, target);
      pair.truth = read_homography_file((folder / ("H1to" + std::to_string(target) + "p")).string());
      pairs.push_back(std::move(pair));
    }
  }
  return pairs;
}

}  // namespace aief::eval
